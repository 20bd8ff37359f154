// G1 Gregory networks and the OpenSubdiv limit surface behind one interface.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/surface/surface.hpp"
#include "surface/face_stencil.hpp"
#include "surface_test_meshes.hpp"

using namespace kiri::geometry;
using namespace kiri::test;

namespace {

glm::dvec2 side_param(int s, double t)
{
    switch (s) {
    case 0: return {t, 0.0};
    case 1: return {1.0, t};
    case 2: return {1.0 - t, 1.0};
    default: return {0.0, 1.0 - t};
    }
}

struct SeamStats {
    double gap = 0.0, angle = 0.0;
    int edges = 0, samples = 0;
};

// C0 gap and normal angle at 17 points (corners included) along every shared edge.
SeamStats seams(const Surface& s, const PolyMesh& m)
{
    SeamStats st;
    for (auto e : m.edges()) {
        if (m.is_boundary(e))
            continue;
        ++st.edges;
        const auto h0 = m.halfedge_handle(e, 0), h1 = m.halfedge_handle(e, 1);
        auto side_of = [&](PolyMesh::HalfedgeHandle h) {
            int k = 0, s0 = -1;
            std::vector<PolyMesh::VertexHandle> c;
            for (auto v : m.fv_range(m.face_handle(h)))
                c.push_back(v);
            for (k = 0; k < 4; ++k)
                if (c[k] == m.from_vertex_handle(h) && c[(k + 1) % 4] == m.to_vertex_handle(h))
                    s0 = k;
            return s0;
        };
        const int fa = m.face_handle(h0).idx(), fb = m.face_handle(h1).idx();
        const int sa = side_of(h0), sb = side_of(h1);
        for (int i = 0; i <= 16; ++i) {
            const double t = i / 16.0;
            const glm::dvec2 a = side_param(sa, t), b = side_param(sb, 1.0 - t);
            const PatchPoint pa = s.evaluate(fa, a.x, a.y), pb = s.evaluate(fb, b.x, b.y);
            st.gap = std::max(st.gap, glm::length(pa.position - pb.position));
            st.angle = std::max(
                st.angle, std::atan2(glm::length(glm::cross(pa.normal, pb.normal)), glm::dot(pa.normal, pb.normal)));
            ++st.samples;
        }
    }
    return st;
}

std::vector<glm::dvec3> points_of(const PolyMesh& m)
{
    std::vector<glm::dvec3> p;
    for (auto v : m.vertices())
        p.push_back({m.point(v)[0], m.point(v)[1], m.point(v)[2]});
    return p;
}

const double kUV[] = {0.0, 1e-300, 0.2, 0.5, 0.77, 1.0};

}  // namespace

TEST(SurfaceNetwork, RegularGridIsTheBicubicBSplineOfOpenSubdiv)
{
    PolyMesh m = grid_mesh(6, 5, 10.0, [](double x, double y) { return 3.0 * std::sin(0.1 * x) * std::cos(0.13 * y); });
    bump(m, 2.0, 1);
    const auto g = make_surface(m, SurfaceKind::gregory);
    const auto c = make_surface(m, SurfaceKind::catmull_clark);
    ASSERT_EQ(g->num_faces(), 30);
    ASSERT_EQ(c->num_faces(), 30);
    double worst = 0.0, worst_d = 0.0;
    for (int f = 0; f < g->num_faces(); ++f)  // every face, border faces and corners included
        for (double u : kUV)
            for (double v : kUV) {
                const PatchPoint a = g->evaluate(f, u, v), b = c->evaluate(f, u, v);
                worst = std::max(worst, glm::length(a.position - b.position));
                worst_d = std::max({worst_d, glm::length(a.du - b.du), glm::length(a.dv - b.dv)});
            }
    std::printf("regular grid: max |p_gregory - p_opensubdiv| %.3g m, derivatives %.3g m\n", worst, worst_d);
    EXPECT_LT(worst, 1e-10);
    EXPECT_LT(worst_d, 1e-9);
}

TEST(SurfaceNetwork, SharedEdgesAreC0AndG1)
{
    struct Case {
        const char* name;
        PolyMesh mesh;
    };
    std::vector<Case> cases;
    PolyMesh grid = grid_mesh(5, 4, 10.0, [](double, double) { return 0.0; });
    bump(grid, 3.0, 2);
    cases.push_back({"grid", grid});
    for (int n : {3, 5, 6}) {
        PolyMesh f = fan_mesh(n);
        bump(f, 1.5, 10 + n);
        cases.push_back({n == 3 ? "valence 3" : n == 5 ? "valence 5" : "valence 6", f});
    }
    // Concave boundary corner: a grid without one corner face (a boundary vertex with 3 faces).
    PolyMesh l = grid_mesh(4, 4, 10.0, [](double x, double y) { return 0.02 * x * y; });
    l.request_face_status();
    l.request_edge_status();
    l.request_vertex_status();
    l.delete_face(PolyMesh::FaceHandle(15), true);
    l.garbage_collection();
    bump(l, 1.0, 3);
    cases.push_back({"concave boundary", l});
    for (const auto& c : cases) {
        const auto s = make_surface(c.mesh, SurfaceKind::gregory);
        const SeamStats st = seams(*s, c.mesh);
        EXPECT_GT(st.edges, 10) << c.name;
        EXPECT_LE(st.gap, 1e-12) << c.name;
        EXPECT_LE(st.angle, 1e-9) << c.name;
        RecordProperty(std::string(c.name) + " max gap, max angle",
                       std::to_string(st.gap) + ", " + std::to_string(st.angle));
        std::printf("%-18s edges %3d samples %5d  max gap %.3g m  max normal angle %.3g rad\n", c.name, st.edges,
                    st.samples, st.gap, st.angle);
        // The limit surface of the same mesh is C0 and smooth too (a sanity check of the
        // harness, with OpenSubdiv's own accuracy).
        const SeamStats so = seams(*make_surface(c.mesh, SurfaceKind::catmull_clark), c.mesh);
        EXPECT_LE(so.gap, 1e-9) << c.name;
    }
}

TEST(SurfaceNetwork, PlanarMeshGivesAPlane)
{
    for (int n : {3, 5, 6}) {
        const PolyMesh m = fan_mesh(n);
        for (auto kind : {SurfaceKind::gregory, SurfaceKind::catmull_clark}) {
            const auto s = make_surface(m, kind);
            for (int f = 0; f < s->num_faces(); ++f)
                for (double u : kUV)
                    for (double v : kUV) {
                        const PatchPoint p = s->evaluate(f, u, v);
                        EXPECT_NEAR(p.position.z, 0.0, 1e-12);
                        EXPECT_NEAR(std::abs(p.normal.z), 1.0, 1e-12);
                    }
        }
    }
}

TEST(SurfaceNetwork, WeightsReproduceEvaluationAndRefitKeepsTopology)
{
    PolyMesh m = fan_mesh(5);
    bump(m, 1.0, 4);
    for (auto kind : {SurfaceKind::gregory, SurfaceKind::catmull_clark}) {
        auto s = make_surface(m, kind);
        // Refit: new z for every vertex, then compare with a surface built from scratch.
        PolyMesh m2 = m;
        bump(m2, 2.0, 5);
        s->set_control_points(points_of(m2));
        const auto fresh = make_surface(m2, kind);
        std::vector<double> w, wu, wv;
        for (int f = 0; f < s->num_faces(); ++f) {
            const auto sup = s->support(f);
            w.resize(sup.size());
            wu.resize(sup.size());
            wv.resize(sup.size());
            for (double u : {0.0, 0.3, 0.9})
                for (double v : {0.1, 0.5, 1.0}) {
                    const PatchPoint a = s->evaluate(f, u, v), b = fresh->evaluate(f, u, v);
                    EXPECT_LT(glm::length(a.position - b.position), 1e-12) << to_string(kind);
                    s->weights(f, u, v, w, wu, wv);
                    glm::dvec3 p(0.0), pu(0.0), pv(0.0);
                    double sum = 0.0;
                    for (std::size_t k = 0; k < sup.size(); ++k) {
                        const glm::dvec3 x = s->control_points()[sup[k]];
                        p += w[k] * x;
                        pu += wu[k] * x;
                        pv += wv[k] * x;
                        sum += w[k];
                    }
                    EXPECT_NEAR(sum, 1.0, 1e-13);
                    EXPECT_LT(glm::length(p - a.position), 1e-11) << to_string(kind);
                    EXPECT_LT(glm::length(pu - a.du), 1e-10) << to_string(kind);
                    EXPECT_LT(glm::length(pv - a.dv), 1e-10) << to_string(kind);
                }
        }
        EXPECT_THROW(s->set_control_points(std::vector<glm::dvec3>(3)), kiri::InputError);
        EXPECT_THROW(s->evaluate(-1, 0.5, 0.5), kiri::InputError);
    }
}

TEST(SurfaceNetwork, FogStencilsMatchTheSurfaceAndTheirSecondDerivatives)
{
    PolyMesh m = fan_mesh(6);
    bump(m, 1.0, 6);
    const auto s = make_surface(m, SurfaceKind::gregory);
    const auto st = make_gregory_stencils(m);
    ASSERT_EQ(st->num_faces(), s->num_faces());
    FaceWeights a, b, c;
    const double h = 1e-5;
    for (int f = 0; f < s->num_faces(); f += 7) {
        ASSERT_EQ(st->support(f).size(), s->support(f).size());
        for (double u : {0.2, 0.5, 0.8})
            for (double v : {0.3, 0.6}) {
                st->weights(f, u, v, a, 2);
                std::vector<double> w(a.w.size()), wu(w.size()), wv(w.size());
                s->weights(f, u, v, w, wu, wv);
                for (std::size_t k = 0; k < w.size(); ++k) {
                    EXPECT_NEAR(a.w[k], w[k], 1e-14);
                    EXPECT_NEAR(a.wu[k], wu[k], 1e-13);
                }
                st->weights(f, u + h, v, b);
                st->weights(f, u - h, v, c);
                for (std::size_t k = 0; k < w.size(); ++k) {
                    EXPECT_NEAR(a.wuu[k], (b.wu[k] - c.wu[k]) / (2 * h), 1e-6);
                    EXPECT_NEAR(a.wuv[k], (b.wv[k] - c.wv[k]) / (2 * h), 1e-6);
                }
                st->weights(f, u, v + h, b);
                st->weights(f, u, v - h, c);
                for (std::size_t k = 0; k < w.size(); ++k)
                    EXPECT_NEAR(a.wvv[k], (b.wv[k] - c.wv[k]) / (2 * h), 1e-6);
            }
    }
}

TEST(SurfaceNetworkStress, HugeOffsetAndBatches)
{
    PolyMesh m = fan_mesh(5);
    bump(m, 1.0, 7);
    PolyMesh far = m;
    const glm::dvec3 off(1e7, 1e7, 1e3);
    for (auto v : far.vertices())
        far.set_point(v, far.point(v) + PolyMesh::Point(off.x, off.y, off.z));
    for (auto kind : {SurfaceKind::gregory, SurfaceKind::catmull_clark}) {
        const auto a = make_surface(m, kind), b = make_surface(far, kind);
        std::vector<double> us, vs;
        for (double u : kUV)
            for (double v : kUV) {
                us.push_back(u);
                vs.push_back(v);
            }
        for (int f = 0; f < a->num_faces(); ++f) {
            const PatchSamples pa = a->evaluate(f, us, vs), pb = b->evaluate(f, us, vs);
            for (std::size_t i = 0; i < us.size(); ++i) {
                EXPECT_LT(glm::length(pb.position(i) - off - pa.position(i)), 1e-8) << to_string(kind);
                EXPECT_LT(glm::length(pb.du(i) - pa.du(i)), 1e-7);
                // The inputs themselves are rounded at 1e7 (ulp 1.9e-9 m) on 2.5 m patches.
                EXPECT_LT(glm::length(pb.normal(i) - pa.normal(i)), 1e-8);
                const PatchPoint single = a->evaluate(f, us[i], vs[i]);
                EXPECT_LT(glm::length(single.position - pa.position(i)), 1e-12);
            }
        }
    }
}

TEST(SurfaceNetwork, RefusesNonQuads)
{
    PolyMesh m;
    auto a = m.add_vertex({0, 0, 0}), b = m.add_vertex({1, 0, 0}), c = m.add_vertex({0, 1, 0});
    m.add_face(a, b, c);
    EXPECT_THROW(make_surface(m, SurfaceKind::gregory), kiri::InputError);
}

TEST(SurfaceNetworkStress, CollapsedEdgeAndZeroAreaFacesStayFinite)
{
    // Two neighbouring vertices on top of each other (a collapsed edge), and a face whose four
    // corners coincide (zero area): both surfaces stay finite with unit normals everywhere.
    PolyMesh m = grid_mesh(4, 4, 10.0, [](double x, double y) { return 0.01 * x * y; });
    m.set_point(PolyMesh::VertexHandle(7), m.point(PolyMesh::VertexHandle(6)));
    for (int v : {18, 19, 23})
        m.set_point(PolyMesh::VertexHandle(v), m.point(PolyMesh::VertexHandle(24)));
    for (auto kind : {SurfaceKind::gregory, SurfaceKind::catmull_clark}) {
        const auto s = make_surface(m, kind);
        std::vector<double> us, vs;
        for (double u : kUV)
            for (double v : kUV) {
                us.push_back(u);
                vs.push_back(v);
            }
        for (int f = 0; f < s->num_faces(); ++f) {
            const PatchSamples p = s->evaluate(f, us, vs);
            for (std::size_t i = 0; i < us.size(); ++i) {
                for (const glm::dvec3& q : {p.position(i), p.du(i), p.dv(i), p.normal(i)})
                    ASSERT_TRUE(std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z)) << to_string(kind);
                EXPECT_NEAR(glm::length(p.normal(i)), 1.0, 1e-12) << to_string(kind) << " face " << f;
            }
        }
    }
}
