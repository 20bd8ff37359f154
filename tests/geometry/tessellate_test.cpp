#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <random>

#include <glm/geometric.hpp>

#include "fog_test_terrains.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/fog/tessellate.hpp"

using namespace kiri::geometry;

namespace {
BaseSurface fitted_hills(SurfaceKind kind, double patch = 250.0)
{
    static const Terrain t(kiri::test::make_heightfield(101, 101, 20.0, -1000.0, -1000.0, kiri::test::hills));
    const std::vector<glm::dvec2> poly = {{-900, -850}, {880, -700}, {700, 800}, {-600, 650}};
    BaseSurface s(build_control_mesh({poly}, t, {patch}), kind);
    FitOptions o;
    o.smoothness = 0.01;
    o.smoothing_length = 100.0;
    s.fit(t, o);
    return s;
}

// Independent check of the distance to the exact surface: random points in every triangle.
double random_error(const BaseSurface& s, const TriMesh& m)
{
    OpenMesh::VPropHandleT<int> pid;
    EXPECT_TRUE(m.get_property_handle(pid, patch_id_property));
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    double e = 0.0;
    for (auto f : m.faces()) {
        std::array<TriMesh::VertexHandle, 3> v;
        int c = 0;
        for (auto vh : m.fv_range(f))
            v[c++] = vh;
        for (int k = 0; k < 4; ++k) {
            double a = U(rng), b = U(rng);
            if (a + b > 1.0) {
                a = 1.0 - a;
                b = 1.0 - b;
            }
            const double w[3] = {1.0 - a - b, a, b};
            double u = 0, vv = 0;
            glm::dvec3 p(0.0);
            for (int i = 0; i < 3; ++i) {
                u += w[i] * m.texcoord2D(v[i])[0];
                vv += w[i] * m.texcoord2D(v[i])[1];
                const auto q = m.point(v[i]);
                p += w[i] * glm::dvec3(q[0], q[1], q[2]);
            }
            e = std::max(e, glm::length(s.evaluate(m.property(pid, v[0]), u, vv) - p));
        }
    }
    return e;
}

// Welds vertices at exactly equal positions and counts the edges used by one triangle only:
// with no cracks and no T-junctions these are exactly the control mesh's border, each split
// into its level's segments.
std::size_t open_edges_after_exact_weld(const TriMesh& m)
{
    std::map<std::array<double, 3>, int> id;
    std::vector<int> weld(m.n_vertices());
    for (auto v : m.vertices()) {
        const auto p = m.point(v);
        weld[v.idx()] = id.emplace(std::array<double, 3>{p[0], p[1], p[2]}, int(id.size())).first->second;
    }
    std::map<std::pair<int, int>, int> uses;
    for (auto f : m.faces()) {
        int c[3], k = 0;
        for (auto v : m.fv_range(f))
            c[k++] = weld[v.idx()];
        for (int e = 0; e < 3; ++e)
            ++uses[{std::min(c[e], c[(e + 1) % 3]), std::max(c[e], c[(e + 1) % 3])}];
    }
    std::size_t open = 0;
    for (const auto& [e, n] : uses) {
        EXPECT_LE(n, 2);
        open += n == 1;
    }
    return open;
}

std::size_t border_segments(const BaseSurface& s, const Tessellation& t)
{
    const PolyMesh& cm = s.control().mesh;
    std::size_t n = 0;
    for (auto h : cm.halfedges())
        if (cm.is_boundary(h))
            n += std::size_t(t.patch_level[cm.face_handle(cm.opposite_halfedge_handle(h)).idx()]);
    return n;
}
}  // namespace

TEST(Tessellate, UniformErrorFallsWithLevel)
{
    for (auto kind : {SurfaceKind::catmull_clark, SurfaceKind::gregory}) {
        const BaseSurface s = fitted_hills(kind);
        double previous = 1e300, first = 0.0;
        for (int level : {1, 2, 4, 8, 16}) {
            const Tessellation t = tessellate(s, {level});
            EXPECT_EQ(t.mesh.n_faces(), std::size_t(2 * level * level * s.num_patches()));
            EXPECT_LT(t.max_error, previous) << "level " << level;
            if (level == 16) {
                EXPECT_LT(t.max_error, first / 10.0);  // about O(1/N^2)
            }
            if (level == 2)
                first = t.max_error;
            EXPECT_LE(random_error(s, t.mesh), t.max_error * 1.01 + 1e-12);
            previous = t.max_error;
        }
    }
}

TEST(Tessellate, AdaptiveMeetsItsTolerance)
{
    for (auto kind : {SurfaceKind::catmull_clark, SurfaceKind::gregory})
        for (double tol : {2.0, 0.5, 0.25}) {
            const BaseSurface s = fitted_hills(kind);
            const Tessellation t = tessellate(s, {8, tol});
            EXPECT_LE(t.max_error, tol);
            EXPECT_LE(random_error(s, t.mesh), tol);
            const auto [lo, hi] = std::minmax_element(t.patch_level.begin(), t.patch_level.end());
            EXPECT_LT(*lo, *hi) << "expected mixed levels at tolerance " << tol;
            EXPECT_EQ(open_edges_after_exact_weld(t.mesh), border_segments(s, t)) << "crack at " << tol;
        }
}

TEST(Tessellate, UniformIsCrackFreeAndCarriesAttributes)
{
    const BaseSurface s = fitted_hills(SurfaceKind::catmull_clark);
    const Tessellation t = tessellate(s, {5});
    EXPECT_EQ(open_edges_after_exact_weld(t.mesh), border_segments(s, t));
    OpenMesh::VPropHandleT<int> pid;
    ASSERT_TRUE(t.mesh.get_property_handle(pid, patch_id_property));
    ASSERT_TRUE(t.mesh.has_vertex_normals());
    for (auto v : t.mesh.vertices()) {
        EXPECT_NEAR(t.mesh.normal(v).norm(), 1.0, 1e-12);
        EXPECT_GT(t.mesh.normal(v)[2], 0.0);
        const auto uv = t.mesh.texcoord2D(v);
        EXPECT_TRUE(uv[0] >= 0.0 && uv[0] <= 1.0 && uv[1] >= 0.0 && uv[1] <= 1.0);
        const int p = t.mesh.property(pid, v);
        ASSERT_TRUE(p >= 0 && p < s.num_patches());
        const glm::dvec3 e = s.evaluate(p, uv[0], uv[1]);
        const auto q = t.mesh.point(v);
        EXPECT_LT(glm::length(e - glm::dvec3(q[0], q[1], q[2])), 1e-9);  // vertices on the surface
    }
    // Triangles face up (counter-clockwise seen from above).
    for (auto f : t.mesh.faces()) {
        std::vector<TriMesh::Point> p;
        for (auto v : t.mesh.fv_range(f))
            p.push_back(t.mesh.point(v));
        EXPECT_GT(((p[1] - p[0]) % (p[2] - p[0]))[2], 0.0);
    }
    EXPECT_THROW(tessellate(s, {0}), kiri::InputError);
    EXPECT_THROW(tessellate(s, {4, -1.0}), kiri::InputError);
}
