#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "fog_test_terrains.hpp"
#include "kiri/geometry/fog/base_surface.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/fog/fog_target.hpp"
#include "kiri/geometry/surface/surface.hpp"
#include "surface/face_stencil.hpp"

using namespace kiri::geometry;
using kiri::test::make_heightfield;

namespace {
const SurfaceKind kKinds[] = {SurfaceKind::catmull_clark, SurfaceKind::gregory};

double plane(double x, double y) { return 500.0 + 0.3 * x - 0.2 * y; }

Terrain terrain_of(double (*f)(double, double), double off = 0.0)
{
    return Terrain(make_heightfield(101, 101, 20.0, -1000.0 + off, -1000.0 + off,
                                    [&](double x, double y) { return f(x - off, y - off); }));
}

BaseSurface surface_over(const Terrain& t, const Footprint& fp, double patch, SurfaceKind kind)
{
    return BaseSurface(build_control_mesh(fp, t, {patch}), kind);
}

// Min of surface - terrain at the fit's own samples, recomputed through evaluate().
double min_clearance_at_samples(const BaseSurface& s, const Terrain& t, int K)
{
    double m = 1e300;
    for (int f = 0; f < s.num_patches(); ++f)
        for (int b = 0; b < K; ++b)
            for (int a = 0; a < K; ++a) {
                const glm::dvec3 p = s.evaluate(f, (a + 0.5) / K, (b + 0.5) / K);
                m = std::min(m, p.z - t.height(p.x, p.y));
            }
    return m;
}
}  // namespace

TEST(BaseSurfaceFit, PlaneIsFittedExactly)
{
    const Terrain t = terrain_of(plane);
    const std::vector<glm::dvec2> poly = {{-900, -850}, {880, -700}, {700, 800}, {-600, 650}};
    for (auto kind : kKinds)
        for (double smooth : {0.0, 0.5}) {
            BaseSurface s = surface_over(t, {poly}, 250.0, kind);
            FitOptions o;
            o.smoothing_length = 0.0;
            o.offset = 20.0;
            o.clearance = 5.0;
            o.smoothness = smooth;
            const FitReport r = s.fit(t, o);
            EXPECT_LT(r.max_deviation, 1e-6) << to_string(kind) << " smoothness " << smooth;
            EXPECT_NEAR(r.min_clearance, 20.0, 1e-6);
            EXPECT_EQ(r.lift, 0.0);
            EXPECT_EQ(r.active_constraints, 0);
            for (double u : {0.0, 0.3, 1.0}) {
                const glm::dvec3 p = s.evaluate(s.num_patches() / 2, u, 1.0 - u);
                EXPECT_NEAR(p.z, plane(p.x, p.y) + 20.0, 1e-6);
            }
        }
}

TEST(BaseSurfaceFit, BlanketNeverBelowTerrainPlusClearance)
{
    const Terrain t = terrain_of(kiri::test::hills);
    for (auto kind : kKinds) {
        BaseSurface s = surface_over(t, rectangle_footprint({-950, -950}, {950, 950}), 200.0, kind);
        FitOptions o;
        o.offset = 10.0;
        o.clearance = 15.0;
        o.smoothing_length = 150.0;
        const FitReport r = s.fit(t, o);
        EXPECT_GE(r.min_clearance, 15.0) << to_string(kind);
        EXPECT_LT(r.min_clearance, 15.5);  // the sharp ridge holds it down: it touches
        EXPECT_GT(r.active_constraints, 0);
        EXPECT_GE(min_clearance_at_samples(s, t, r.samples_per_patch), 15.0 - 1e-9);
        EXPECT_LT(r.rms_deviation, 80.0);  // the 150 m ridge is far above its smoothed target
        EXPECT_GE(r.max_deviation, r.rms_deviation);
        // Every terrain vertex under the (snapped) mesh [-950, 950]^2 is a sample: 95 x 95.
        EXPECT_EQ(r.grid_vertex_samples, 95 * 95);
        EXPECT_EQ(r.samples, (long long)s.num_patches() * r.samples_per_patch * r.samples_per_patch + 95 * 95);
        // Between samples too: the terrain is linear on its triangles, so over the ridges
        // (where the surface is concave) the clearance is smallest at the terrain's vertices.
        // Not a guarantee where the surface is convex: measured 14.76 m (5% allowed).
        EXPECT_GE(min_clearance_at_samples(s, t, 64), 15.0 * 0.95);
    }
}

TEST(BaseSurfaceFit, LakeIsFlatAtItsAltitude)
{
    const Terrain t = terrain_of(kiri::test::hills);
    for (auto kind : kKinds) {
        BaseSurface s = surface_over(t, rectangle_footprint({-950, -950}, {950, 950}), 200.0, kind);
        FitOptions o;
        o.mode = FitMode::lake;
        o.altitude = 420.0;
        const FitReport r = s.fit(t, o);
        EXPECT_LT(r.max_deviation, 1e-9);
        for (double z : s.heights())
            EXPECT_NEAR(z, 420.0, 1e-9);
        EXPECT_NEAR(s.evaluate(3, 0.2, 0.7).z, 420.0, 1e-9);
        EXPECT_GT(r.fog_fraction, 0.2);
        EXPECT_LT(r.fog_fraction, 0.8);
        EXPECT_LT(r.min_clearance, 0.0);  // the ridge rises through the lake
    }
}

TEST(BaseSurfaceFit, RefitChangesOnlyHeights)
{
    const Terrain t = terrain_of(plane);
    BaseSurface s = surface_over(t, rectangle_footprint({-900, -900}, {900, 900}), 300.0, SurfaceKind::catmull_clark);
    FitOptions o;
    o.smoothing_length = 0.0;
    o.offset = 20.0;
    EXPECT_FALSE(s.fit(t, o).samples_reused);
    const auto h1 = s.heights();
    const auto p1 = s.control().mesh.point(PolyMesh::VertexHandle(5));
    o.offset = 45.0;
    EXPECT_TRUE(s.fit(t, o).samples_reused);
    const auto h2 = s.heights();
    const auto p2 = s.control().mesh.point(PolyMesh::VertexHandle(5));
    EXPECT_EQ(p1[0], p2[0]);
    EXPECT_EQ(p1[1], p2[1]);
    for (std::size_t k = 0; k < h1.size(); ++k)
        EXPECT_NEAR(h2[k] - h1[k], 25.0, 1e-6);
}

TEST(BaseSurfaceFit, ClearErrors)
{
    const Terrain t = terrain_of(kiri::test::hills);
    BaseSurface s = surface_over(t, rectangle_footprint({-500, -500}, {500, 500}), 250.0, SurfaceKind::catmull_clark);
    FitOptions o;
    o.clearance = 300.0;
    o.thickness = 200.0;
    try {
        s.fit(t, o);
        FAIL() << "no error";
    } catch (const kiri::InputError& e) {
        EXPECT_EQ(e.field(), "clearance");
        EXPECT_NE(std::string(e.what()).find("thickness 200"), std::string::npos) << e.what();
    }
    FitOptions lake;
    lake.mode = FitMode::lake;
    lake.altitude = 100.0;
    EXPECT_THROW(s.fit(t, lake), kiri::InputError);
    FitOptions bad;
    bad.smoothness = NAN;
    EXPECT_THROW(s.fit(t, bad), kiri::InputError);
}

TEST(BaseSurfaceFit, HugeCoordinatesGiveTheSameFit)
{
    const double off = 1e7;
    const Terrain a = terrain_of(kiri::test::hills), b = terrain_of(kiri::test::hills, off);
    const std::vector<glm::dvec2> poly = {{-900, -850}, {880, -700}, {700, 800}, {-600, 650}};
    std::vector<glm::dvec2> shifted = poly;
    for (auto& v : shifted)
        v += glm::dvec2(off);
    BaseSurface sa = surface_over(a, {poly}, 250.0, SurfaceKind::catmull_clark);
    BaseSurface sb = surface_over(b, {shifted}, 250.0, SurfaceKind::catmull_clark);
    const FitReport ra = sa.fit(a, {}), rb = sb.fit(b, {});
    EXPECT_NEAR(ra.max_deviation, rb.max_deviation, 1e-6);
    EXPECT_NEAR(ra.min_clearance, rb.min_clearance, 1e-6);
    const auto ha = sa.heights(), hb = sb.heights();
    for (std::size_t k = 0; k < ha.size(); ++k)
        EXPECT_NEAR(ha[k], hb[k], 1e-6);
    const glm::dvec3 pa = sa.evaluate(2, 0.4, 0.6), pb = sb.evaluate(2, 0.4, 0.6);
    EXPECT_NEAR(pb.x - off, pa.x, 1e-6);
    EXPECT_NEAR(pb.z, pa.z, 1e-6);
}

TEST(BaseSurfaceFit, FootprintSmallerThanAPatch)
{
    const Terrain t = terrain_of(kiri::test::hills);
    BaseSurface s = surface_over(t, rectangle_footprint({100, 100}, {160, 140}), 500.0, SurfaceKind::catmull_clark);
    ASSERT_EQ(s.num_patches(), 1);
    FitOptions o;
    o.clearance = 5.0;
    const FitReport r = s.fit(t, o);
    EXPECT_GE(r.min_clearance, 5.0);
    const glm::dvec3 c = s.evaluate(0, 0.5, 0.5);
    EXPECT_NEAR(c.x, 130.0, 1e-9);
    EXPECT_NEAR(c.y, 120.0, 1e-9);
}

TEST(BaseSurfaceFit, NodataCellsAreLeftOut)
{
    Heightfield hf = make_heightfield(101, 101, 20.0, -1000.0, -1000.0, kiri::test::hills);
    for (int j = 40; j < 60; ++j)
        for (int i = 30; i < 70; ++i) {
            hf.valid[std::size_t(j) * hf.nx + i] = 0;
            hf.z[std::size_t(j) * hf.nx + i] = 5000.0;  // a wild fill value must not matter
        }
    const Terrain t(std::move(hf));
    BaseSurface s = surface_over(t, rectangle_footprint({-950, -950}, {950, 950}), 200.0, SurfaceKind::catmull_clark);
    FitOptions o;
    o.smoothing_length = 150.0;
    const FitReport r = s.fit(t, o);
    EXPECT_GT(r.nodata_samples, 0);
    EXPECT_GE(r.min_clearance, o.clearance);
    for (double z : s.heights()) {
        EXPECT_TRUE(std::isfinite(z));
        EXPECT_LT(z, 1200.0);
    }
}

TEST(BaseSurfaceFit, NearlyFlatAndCliff)
{
    const Terrain flat(
        make_heightfield(101, 101, 20.0, -1000.0, -1000.0, [](double x, double) { return 250.0 + 1e-9 * x; }));
    BaseSurface s =
        surface_over(flat, rectangle_footprint({-900, -900}, {900, 900}), 300.0, SurfaceKind::catmull_clark);
    const FitReport r = s.fit(flat, {});
    EXPECT_LT(r.max_deviation, 1e-6);
    const Terrain cliff(
        make_heightfield(101, 101, 20.0, -1000.0, -1000.0, [](double x, double) { return x < 10.0 ? 300.0 : 700.0; }));
    BaseSurface c =
        surface_over(cliff, rectangle_footprint({-900, -900}, {900, 900}), 300.0, SurfaceKind::catmull_clark);
    FitOptions o;
    o.clearance = 8.0;
    const FitReport rc = c.fit(cliff, o);
    EXPECT_GE(rc.min_clearance, 8.0);
    EXPECT_GE(min_clearance_at_samples(c, cliff, rc.samples_per_patch), 8.0 - 1e-9);
    for (double z : c.heights())
        EXPECT_TRUE(std::isfinite(z));
}

TEST(SurfaceKinds, GregoryEqualsCatmullClarkOnARegularGrid)
{
    // Regular interior and boundary: LSNC and the phantom boundary rules give the bicubic
    // B-spline patches that the Catmull-Clark limit is made of ([Loop09]).
    const Terrain t = terrain_of(kiri::test::hills);
    const Footprint fp = rectangle_footprint({-900, -900}, {900, 900});
    BaseSurface g = surface_over(t, fp, 300.0, SurfaceKind::gregory);
    BaseSurface c = surface_over(t, fp, 300.0, SurfaceKind::catmull_clark);
    double worst = 0.0;
    for (int f = 0; f < g.num_patches(); ++f)
        for (double u : {0.0, 0.1, 0.5, 0.77, 1.0})
            for (double v : {0.0, 0.3, 0.5, 1.0}) {
                glm::dvec3 gu, gv, cu, cv;
                const glm::dvec3 pg = g.evaluate(f, u, v, &gu, &gv), pc = c.evaluate(f, u, v, &cu, &cv);
                worst = std::max({worst, glm::length(pg - pc), glm::length(gu - cu), glm::length(gv - cv)});
            }
    EXPECT_LT(worst, 1e-8);
}

TEST(SurfaceKinds, GregoryPatchesMeetAlongEdges)
{
    const Terrain t = terrain_of(kiri::test::hills);
    const std::vector<glm::dvec2> poly = {{-900, -850}, {880, -700}, {100, 0}, {700, 800}, {-600, 650}};
    BaseSurface g = surface_over(t, {poly}, 200.0, SurfaceKind::gregory);
    const PolyMesh& m = g.control().mesh;
    auto corner_index = [&](PolyMesh::FaceHandle f, PolyMesh::VertexHandle v) {
        int k = 0;
        for (auto fv : m.fv_range(f)) {
            if (fv == v)
                return k;
            ++k;
        }
        return -1;
    };
    const glm::dvec2 corner_uv[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    int edges = 0;
    double worst = 0.0;
    for (auto e : m.edges()) {
        if (m.is_boundary(e))
            continue;
        const auto h = m.halfedge_handle(e, 0), o = m.halfedge_handle(e, 1);
        const auto a = m.from_vertex_handle(h), b = m.to_vertex_handle(h);
        const auto F = m.face_handle(h), G = m.face_handle(o);
        for (double s : {0.0, 0.25, 0.5, 0.9, 1.0}) {
            const glm::dvec2 uf = glm::mix(corner_uv[corner_index(F, a)], corner_uv[corner_index(F, b)], s);
            const glm::dvec2 ug = glm::mix(corner_uv[corner_index(G, a)], corner_uv[corner_index(G, b)], s);
            worst = std::max(worst, glm::length(g.evaluate(F.idx(), uf.x, uf.y) - g.evaluate(G.idx(), ug.x, ug.y)));
        }
        ++edges;
    }
    EXPECT_GT(edges, 50);
    EXPECT_LT(worst, 1e-9);
}

TEST(FogTarget, SmoothingKeepsPlanesAwayFromTheBorderAndIgnoresNodata)
{
    // A box filter reproduces a linear function wherever its window is whole; normalised
    // convolution keeps constants exact everywhere, and nodata values do not leak in.
    Heightfield hf =
        make_heightfield(60, 50, 10.0, 0.0, 0.0, [](double x, double y) { return 3.0 + 0.5 * x - 0.25 * y; });
    const Heightfield s = smooth_heightfield(hf, 20.0);
    for (int j = 15; j < 35; ++j)
        for (int i = 15; i < 45; ++i)
            EXPECT_NEAR(s.at(i, j), hf.at(i, j), 1e-9);
    Heightfield c = make_heightfield(60, 50, 10.0, 0.0, 0.0, [](double, double) { return 7.0; });
    for (int i = 0; i < 60; ++i) {
        c.valid[20 * 60 + i] = 0;
        c.z[20 * 60 + i] = 1e6;
    }
    const Heightfield cs = smooth_heightfield(c, 35.0);
    for (std::size_t k = 0; k < cs.z.size(); ++k) {
        if (c.valid[k]) {
            EXPECT_NEAR(cs.z[k], 7.0, 1e-9);
        }
    }
    EXPECT_NEAR(sample_bilinear(hf, 123.0, 77.0), 3.0 + 0.5 * 123.0 - 0.25 * 77.0, 1e-9);
}

TEST(SurfaceKinds, AgreesWithTheSurfaceModule)
{
    // The fit's stencils (the linear map it solves with) and the surface module (surface.hpp,
    // which evaluate() and the tessellation use) give the same surfaces.
    const Terrain t = terrain_of(kiri::test::hills);
    const std::vector<glm::dvec2> poly = {{-900, -850}, {880, -700}, {100, 0}, {700, 800}, {-600, 650}};
    for (auto [kind, skind] : {std::pair{SurfaceKind::catmull_clark, SurfaceKind::catmull_clark},
                               std::pair{SurfaceKind::gregory, SurfaceKind::gregory}}) {
        BaseSurface b = surface_over(t, {poly}, 200.0, kind);
        b.fit(t, {});
        const auto s = make_surface(b.control().mesh, skind);
        double worst = 0.0;
        for (int f = 0; f < b.num_patches(); ++f)
            for (double u : {0.0, 0.2, 0.5, 1.0})
                for (double v : {0.0, 0.7, 1.0}) {
                    FaceWeights fw;
                    b.stencils().weights(f, u, v, fw, 1);
                    glm::dvec3 p(0.0), du(0.0), dv(0.0);
                    const auto& S = b.stencils().support(f);
                    for (std::size_t k = 0; k < S.size(); ++k) {
                        const auto c = b.control().mesh.point(PolyMesh::VertexHandle(S[k]));
                        p += fw.w[k] * glm::dvec3(c[0], c[1], c[2]);
                        du += fw.wu[k] * glm::dvec3(c[0], c[1], c[2]);
                        dv += fw.wv[k] * glm::dvec3(c[0], c[1], c[2]);
                    }
                    const PatchPoint q = s->evaluate(f, u, v);
                    worst = std::max(worst, glm::length(b.evaluate(f, u, v) - q.position));
                    worst =
                        std::max({worst, glm::length(p - q.position), glm::length(du - q.du), glm::length(dv - q.dv)});
                }
        EXPECT_LT(worst, 1e-6) << to_string(kind);
    }
}
