#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "fog_test_terrains.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/fog/footprint.hpp"

using namespace kiri::geometry;

namespace {
Terrain flat_terrain(double x0 = -1000.0, double y0 = -1000.0)
{
    return Terrain(kiri::test::make_heightfield(101, 101, 20.0, x0, y0, [](double, double) { return 300.0; }));
}

double distance_to_border(const std::vector<glm::dvec2>& p, glm::dvec2 q)
{
    double best = 1e300;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const glm::dvec2 a = p[i], b = p[(i + 1) % p.size()], ab = b - a;
        const double t = std::clamp(glm::dot(q - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
        best = std::min(best, glm::length(q - (a + t * ab)));
    }
    return best;
}

double min_quad_area(const PolyMesh& m)
{
    double best = 1e300;
    for (auto f : m.faces()) {
        std::vector<glm::dvec2> q;
        for (auto v : m.fv_range(f))
            q.emplace_back(m.point(v)[0], m.point(v)[1]);
        double a = 0.0;
        for (int k = 0; k < 4; ++k)
            a += q[k].x * q[(k + 1) % 4].y - q[(k + 1) % 4].x * q[k].y;
        best = std::min(best, 0.5 * a);
    }
    return best;
}
}  // namespace

TEST(Footprint, RectangleGivesExactGrid)
{
    const Terrain t = flat_terrain();
    const ControlMesh cm = build_control_mesh(rectangle_footprint({-500, -300}, {500, 300}), t, {200.0});
    EXPECT_EQ(cm.num_faces(), 5 * 3);
    EXPECT_EQ(cm.num_vertices(), 6 * 4);
    EXPECT_EQ(cm.boundary_vertices, 2 * (6 + 4) - 4);
    for (auto v : cm.mesh.vertices())
        EXPECT_DOUBLE_EQ(cm.mesh.point(v)[2], 300.0);  // heights from the terrain
    EXPECT_NEAR(min_quad_area(cm.mesh), 200.0 * 200.0, 1e-6);
}

TEST(Footprint, PolygonBorderIsFollowed)
{
    const Terrain t = flat_terrain();
    const std::vector<glm::dvec2> tri = {{-800, -700}, {850, -600}, {-100, 900}};
    const ControlMesh cm = build_control_mesh({tri}, t, {150.0});
    ASSERT_GT(cm.num_faces(), 20);
    EXPECT_GT(cm.snapped_vertices, cm.boundary_vertices / 2);
    double worst = 0.0;  // vertices that could not snap stay within a patch of the border
    for (auto v : cm.mesh.vertices())
        if (cm.mesh.is_boundary(v))
            worst = std::max(worst, distance_to_border(tri, {cm.mesh.point(v)[0], cm.mesh.point(v)[1]}));
    EXPECT_LT(worst, 150.0);
    int on_border = 0;
    for (auto v : cm.mesh.vertices())
        if (cm.mesh.is_boundary(v))
            on_border += distance_to_border(tri, {cm.mesh.point(v)[0], cm.mesh.point(v)[1]}) < 1e-9;
    EXPECT_EQ(on_border, cm.snapped_vertices);
    // The polygon's corners are vertices of the mesh.
    for (const auto& c : tri) {
        double best = 1e300;
        for (auto v : cm.mesh.vertices())
            best = std::min(best, glm::length(glm::dvec2(cm.mesh.point(v)[0], cm.mesh.point(v)[1]) - c));
        EXPECT_LT(best, 1e-9);
    }
    EXPECT_GT(min_quad_area(cm.mesh), 0.0);  // no folded quad
}

TEST(Footprint, SmallerThanOnePatchGivesOnePatchOnThePolygon)
{
    const Terrain t = flat_terrain();
    const ControlMesh cm = build_control_mesh(rectangle_footprint({10, 20}, {60, 50}), t, {500.0});
    ASSERT_EQ(cm.num_faces(), 1);
    for (auto v : cm.mesh.vertices()) {
        const auto p = cm.mesh.point(v);
        EXPECT_TRUE(p[0] == 10.0 || p[0] == 60.0);
        EXPECT_TRUE(p[1] == 20.0 || p[1] == 50.0);
    }
}

TEST(Footprint, InvalidPolygonsAreRefused)
{
    const Terrain t = flat_terrain();
    auto message = [&](const std::vector<glm::dvec2>& p) {
        try {
            build_control_mesh({p}, t, {100.0}, "scene.json");
        } catch (const kiri::InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message({{0, 0}, {200, 100}, {200, 0}, {0, 150}}).find("intersect"), std::string::npos)
        << message({{0, 0}, {200, 100}, {200, 0}, {0, 150}});
    EXPECT_NE(message({{0, 0}, {100, 0}, {200, 0}}).find("no area"), std::string::npos);
    EXPECT_NE(message({{0, 0}, {100, 0}}).find("at least 3"), std::string::npos);
    EXPECT_NE(message({{0, 0}, {100, 0}, {100, 0}, {0, 100}}).find("coincide"), std::string::npos);
    EXPECT_NE(message({{0, 0}, {100, 0}, {NAN, 50}}).find("not finite"), std::string::npos);
    const std::string outside = message({{0, 0}, {1500, 0}, {0, 100}});
    EXPECT_NE(outside.find("outside the terrain"), std::string::npos) << outside;
    EXPECT_EQ(outside.rfind("scene.json: footprint: vertex 1", 0), 0u) << outside;
    EXPECT_THROW(build_control_mesh(rectangle_footprint({0, 0}, {10, 10}), t, {0.0}), kiri::InputError);
    EXPECT_THROW(build_control_mesh(rectangle_footprint({-999, -999}, {999, 999}), t, {0.01}), kiri::LimitError);
}

TEST(Footprint, HugeCoordinatesGiveTheSameMesh)
{
    const double off = 1e7;
    const Terrain a = flat_terrain(), b = flat_terrain(-1000.0 + off, -1000.0 + off);
    const std::vector<glm::dvec2> p = {{-700, -650}, {800, -500}, {600, 700}, {-650, 400}};
    std::vector<glm::dvec2> q = p;
    for (auto& v : q)
        v += glm::dvec2(off);
    const ControlMesh ma = build_control_mesh({p}, a, {170.0}), mb = build_control_mesh({q}, b, {170.0});
    ASSERT_EQ(ma.num_vertices(), mb.num_vertices());
    for (int v = 0; v < ma.num_vertices(); ++v) {
        const auto pa = ma.mesh.point(PolyMesh::VertexHandle(v)), pb = mb.mesh.point(PolyMesh::VertexHandle(v));
        EXPECT_NEAR(pb[0] - off, pa[0], 1e-6);
        EXPECT_NEAR(pb[1] - off, pa[1], 1e-6);
    }
}
