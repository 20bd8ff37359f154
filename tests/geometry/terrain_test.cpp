// Terrain queries on analytic terrains, against closed forms of the piecewise-linear surface
// (each cell split along the diagonal (i,j)-(i+1,j+1)).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <algorithm>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "kiri/geometry/terrain/terrain.hpp"

using kiri::geometry::Heightfield;
using kiri::geometry::Terrain;

namespace {

Heightfield sample(const std::function<double(double, double)>& f, int nx, int ny, double dx, double dy, double x0,
                   double y0)
{
    Heightfield hf;
    hf.nx = nx, hf.ny = ny, hf.dx = dx, hf.dy = dy, hf.x0 = x0, hf.y0 = y0;
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
            hf.z.push_back(f(x0 + i * dx, y0 + j * dy));
    hf.valid.assign(hf.z.size(), 1);
    return hf;
}

void expect_near(const glm::dvec3& a, const glm::dvec3& b, double tol)
{
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

// Plane z = a + b x + c y over a grid with non-square cells and an off-origin corner.
constexpr double pa = 120.0, pb = 0.3, pc = -0.2;
double plane(double x, double y) { return pa + pb * x + pc * y; }
Terrain plane_terrain() { return Terrain(sample(plane, 21, 17, 10.0, 12.5, -100.0, -90.0)); }

// Paraboloid z = a (x^2 + y^2). On a right triangle whose hypotenuse is the cell diagonal the
// linear interpolant of |p|^2 is |p|^2 + R^2 - |p - c|^2, c the cell centre (circumcentre) and
// R^2 = (dx^2 + dy^2) / 4; its gradient is 2 a c, the same on both triangles of a cell.
constexpr double qa = 0.01;
double paraboloid(double x, double y) { return qa * (x * x + y * y); }
constexpr double qdx = 2.0, qdy = 3.0, qx0 = -20.0, qy0 = -21.0;
Terrain paraboloid_terrain() { return Terrain(sample(paraboloid, 21, 15, qdx, qdy, qx0, qy0)); }
glm::dvec2 cell_centre(double x, double y)
{
    const double ci = std::floor((x - qx0) / qdx), cj = std::floor((y - qy0) / qdy);
    return {qx0 + (ci + 0.5) * qdx, qy0 + (cj + 0.5) * qdy};
}
double paraboloid_mesh_height(double x, double y)
{
    const glm::dvec2 c = cell_centre(x, y);
    const double r2 = (qdx * qdx + qdy * qdy) / 4.0;
    return qa * (x * x + y * y + r2 - ((x - c.x) * (x - c.x) + (y - c.y) * (y - c.y)));
}

// Sine ridge z = A sin(k x), constant along y: the mesh is the 1D linear interpolant in x.
constexpr double sA = 50.0, sk = 2.0 * M_PI / 400.0, sdx = 10.0;
double ridge(double x, double) { return sA * std::sin(sk * x); }
Terrain ridge_terrain() { return Terrain(sample(ridge, 81, 11, sdx, 20.0, 0.0, -100.0)); }
double ridge_mesh_height(double x)
{
    const double i = std::floor(x / sdx), s = x / sdx - i;
    return (1.0 - s) * ridge(i * sdx, 0.0) + s * ridge((i + 1.0) * sdx, 0.0);
}

}  // namespace

TEST(TerrainPlane, HeightAndNormalAreExactEverywhere)
{
    const Terrain t = plane_terrain();
    const glm::dvec3 n = glm::normalize(glm::dvec3(-pb, -pc, 1.0));
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> ux(-100.0, 100.0), uy(-90.0, 110.0);
    for (int k = 0; k < 200; ++k) {
        const double x = ux(rng), y = uy(rng);
        EXPECT_NEAR(t.height(x, y), plane(x, y), 1e-9);
        expect_near(t.normal(x, y), n, 1e-12);
    }
    // Outside the grid: the nearest edge's value.
    EXPECT_NEAR(t.height(-500.0, 0.0), plane(-100.0, 0.0), 1e-9);
    EXPECT_NEAR(t.height(0.0, 1e6), plane(0.0, 110.0), 1e-9);
}

TEST(TerrainPlane, BoundsSpanTheGrid)
{
    const auto b = plane_terrain().bounds();
    expect_near(b.min, {-100.0, -90.0, plane(-100.0, 110.0)}, 1e-9);
    expect_near(b.max, {100.0, 110.0, plane(100.0, -90.0)}, 1e-9);
}

TEST(TerrainPlane, RayHitsMatchTheClosedForm)
{
    const Terrain t = plane_terrain();
    const glm::dvec3 n = glm::normalize(glm::dvec3(-pb, -pc, 1.0));
    std::mt19937 rng(2);
    // Rays that land inside the grid: at most 0.2 m sideways per metre down, from 200 m.
    std::uniform_real_distribution<double> ux(-60.0, 60.0), uy(-50.0, 70.0), ud(-0.2, 0.2);
    for (int k = 0; k < 100; ++k) {
        const glm::dvec3 o(ux(rng), uy(rng), 200.0);
        const glm::dvec3 d = glm::normalize(glm::dvec3(ud(rng), ud(rng), -1.0));
        // o + t d on z = a + b x + c y.
        const double tt = (pa + pb * o.x + pc * o.y - o.z) / (d.z - pb * d.x - pc * d.y);
        const auto hit = t.intersect_ray(o, d * 3.0);  // the direction need not be unit
        ASSERT_TRUE(hit);
        EXPECT_NEAR(hit->t, tt, 1e-8);
        expect_near(hit->point, o + tt * d, 1e-8);
        expect_near(hit->normal, n, 1e-12);
    }
    // Pointing away, or passing beside the grid: no hit. Degenerate direction: no hit.
    EXPECT_FALSE(t.intersect_ray({0.0, 0.0, 400.0}, {0.0, 0.0, 1.0}));
    EXPECT_FALSE(t.intersect_ray({500.0, 0.0, 400.0}, {0.0, 0.0, -1.0}));
    EXPECT_FALSE(t.intersect_ray({0.0, 0.0, 400.0}, {0.0, 0.0, 0.0}));
    EXPECT_FALSE(t.intersect_ray({0.0, 0.0, 400.0}, {NAN, 0.0, -1.0}));
    // From below, the hit normal still points up.
    const auto below = t.intersect_ray({0.0, 0.0, 0.0}, {0.0, 0.0, 1.0});
    ASSERT_TRUE(below);
    EXPECT_NEAR(below->t, plane(0.0, 0.0), 1e-9);
    expect_near(below->normal, n, 1e-12);
}

TEST(TerrainPlane, ClosestPointIsTheOrthogonalProjection)
{
    const Terrain t = plane_terrain();
    const glm::dvec3 n = glm::normalize(glm::dvec3(-pb, -pc, 1.0));
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> ux(-50.0, 50.0), uy(-40.0, 60.0), uh(-30.0, 30.0);
    for (int k = 0; k < 100; ++k) {
        const double x = ux(rng), y = uy(rng);
        const glm::dvec3 foot(x, y, plane(x, y));
        const glm::dvec3 p = foot + uh(rng) * n;
        expect_near(t.closest_point(p), foot, 1e-8);
    }
}

TEST(TerrainParaboloid, HeightsAndNormalsFollowTheInterpolant)
{
    const Terrain t = paraboloid_terrain();
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> ux(-19.9, 19.9), uy(-20.9, 20.9);
    const double r2 = (qdx * qdx + qdy * qdy) / 4.0;
    for (int k = 0; k < 300; ++k) {
        const double x = ux(rng), y = uy(rng);
        const double h = t.height(x, y);
        EXPECT_NEAR(h, paraboloid_mesh_height(x, y), 1e-10);
        // The interpolant lies above the convex surface by at most a R^2.
        EXPECT_GE(h, paraboloid(x, y) - 1e-12);
        EXPECT_LE(h, paraboloid(x, y) + qa * r2 + 1e-12);
        const glm::dvec2 c = cell_centre(x, y);
        expect_near(t.normal(x, y), glm::normalize(glm::dvec3(-2.0 * qa * c.x, -2.0 * qa * c.y, 1.0)), 1e-12);
    }
    // Grid samples are exact.
    EXPECT_NEAR(t.height(0.0, 0.0), 0.0, 1e-12);
    EXPECT_NEAR(t.height(10.0, 9.0), paraboloid(10.0, 9.0), 1e-12);
}

TEST(TerrainParaboloid, RayHitsLieOnTheSurfaceAndAreFirst)
{
    const Terrain t = paraboloid_terrain();
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> ux(-12.0, 12.0), uy(-12.0, 12.0), ud(-0.2, 0.2);
    for (int k = 0; k < 100; ++k) {
        // Vertical: the hit is straight below at the interpolated height.
        const double x = ux(rng), y = uy(rng);
        const auto v = t.intersect_ray({x, y, 100.0}, {0.0, 0.0, -1.0});
        ASSERT_TRUE(v);
        EXPECT_NEAR(v->t, 100.0 - paraboloid_mesh_height(x, y), 1e-9);
        const glm::dvec2 c = cell_centre(x, y);
        expect_near(v->normal, glm::normalize(glm::dvec3(-2.0 * qa * c.x, -2.0 * qa * c.y, 1.0)), 1e-9);

        // Oblique: on the surface, and every earlier point of the ray is above it.
        const glm::dvec3 o(ux(rng), uy(rng), 30.0);
        const glm::dvec3 d = glm::normalize(glm::dvec3(ud(rng), ud(rng), -1.0));
        const auto hit = t.intersect_ray(o, d);
        ASSERT_TRUE(hit);
        EXPECT_NEAR(glm::length(hit->point - (o + hit->t * d)), 0.0, 1e-9);
        EXPECT_NEAR(hit->point.z, t.height(hit->point.x, hit->point.y), 1e-9);
        for (int s = 0; s < 50; ++s) {
            const glm::dvec3 q = o + (hit->t * s / 50.0) * d;
            EXPECT_GT(q.z, t.height(q.x, q.y) - 1e-9);
        }
    }
}

TEST(TerrainParaboloid, ClosestPointAboveTheApex)
{
    // Around the apex (a grid sample) the four cells are planes through it with gradient
    // (+-a dx, +-a dy): the distance from (0, 0, H) is H / sqrt(1 + a^2 (dx^2 + dy^2)).
    const Terrain t = paraboloid_terrain();
    const double H = 5.0;
    const glm::dvec3 p(0.0, 0.0, H), q = t.closest_point(p);
    EXPECT_NEAR(glm::distance(p, q), H / std::sqrt(1.0 + qa * qa * (qdx * qdx + qdy * qdy)), 1e-9);
    EXPECT_NEAR(q.z, t.height(q.x, q.y), 1e-9);
    EXPECT_NEAR(std::abs(q.x), H * qa * qdx / (1.0 + qa * qa * (qdx * qdx + qdy * qdy)), 1e-9);
}

TEST(TerrainRidge, HeightIsTheLinearInterpolantInX)
{
    const Terrain t = ridge_terrain();
    std::mt19937 rng(6);
    std::uniform_real_distribution<double> ux(0.0, 800.0), uy(-100.0, 100.0);
    for (int k = 0; k < 300; ++k) {
        const double x = ux(rng), y = uy(rng);
        EXPECT_NEAR(t.height(x, y), ridge_mesh_height(x), 1e-10);
        // Interpolation error bound A k^2 dx^2 / 8.
        EXPECT_LE(std::abs(t.height(x, y) - ridge(x, y)), sA * sk * sk * sdx * sdx / 8.0 + 1e-12);
        const double i = std::floor(x / sdx);
        const double slope = (ridge((i + 1) * sdx, 0) - ridge(i * sdx, 0)) / sdx;
        expect_near(t.normal(x, y), glm::normalize(glm::dvec3(-slope, 0.0, 1.0)), 1e-12);
    }
}

TEST(TerrainRidge, HorizontalRayStopsAtTheFirstCrossing)
{
    // From x = 210 (in the trough, z < 0) heading +x at z = 20: the mesh first reaches 20 m
    // on the rising flank past x = 400; solve the linear piece.
    const Terrain t = ridge_terrain();
    const double z = 20.0, y = 3.0;
    double x_hit = -1.0;
    for (int i = 21; i < 80; ++i) {
        const double a = ridge(i * sdx, 0), b = ridge((i + 1) * sdx, 0);
        if ((a - z) * (b - z) <= 0.0 && a < z) {
            x_hit = i * sdx + sdx * (z - a) / (b - a);
            break;
        }
    }
    ASSERT_GT(x_hit, 400.0);
    const auto hit = t.intersect_ray({210.0, y, z}, {1.0, 0.0, 0.0});
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, x_hit - 210.0, 1e-9);
    expect_near(hit->point, {x_hit, y, z}, 1e-9);
}

TEST(TerrainRidge, ClosestPointMatchesThePolylineInXZ)
{
    // Away from the y edges the mesh is the x-z polyline extruded along y: the closest point
    // of a query is the closest point of that polyline, at the same y.
    const Terrain t = ridge_terrain();
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> ux(100.0, 700.0), uy(-20.0, 20.0), uz(-80.0, 80.0);
    for (int k = 0; k < 50; ++k) {
        const glm::dvec3 p(ux(rng), uy(rng), uz(rng));
        double best = INFINITY;
        glm::dvec2 best_q{};
        for (int i = 0; i < 80; ++i) {
            const glm::dvec2 a(i * sdx, ridge(i * sdx, 0)), b((i + 1) * sdx, ridge((i + 1) * sdx, 0));
            const double s = std::clamp(glm::dot(glm::dvec2(p.x, p.z) - a, b - a) / glm::dot(b - a, b - a), 0.0, 1.0);
            const glm::dvec2 q = a + s * (b - a);
            if (const double dist = glm::distance(q, glm::dvec2(p.x, p.z)); dist < best)
                best = dist, best_q = q;
        }
        const glm::dvec3 q = t.closest_point(p);
        EXPECT_NEAR(glm::distance(p, q), best, 1e-8);
        expect_near(q, {best_q.x, p.y, best_q.y}, 1e-6);
    }
}

TEST(TerrainMesh, TopologyAndVertexNormals)
{
    const Terrain t = paraboloid_terrain();
    const auto& m = t.mesh();
    EXPECT_EQ(m.n_vertices(), 21u * 15u);
    EXPECT_EQ(m.n_faces(), 2u * 20u * 14u);
    EXPECT_EQ(m.n_edges(), 20u * 15u + 21u * 14u + 20u * 14u);
    ASSERT_TRUE(m.has_vertex_normals());
    ASSERT_TRUE(m.has_face_normals());
    // Face normals agree with normal() at each face's centroid; vertex normals point up.
    for (const auto f : m.faces()) {
        OpenMesh::Vec3d c(0, 0, 0);
        for (const auto v : f.vertices())
            c += m.point(v) / 3.0;
        const auto fn = m.normal(f);
        expect_near({fn[0], fn[1], fn[2]}, t.normal(c[0], c[1]), 1e-12);
        EXPECT_NEAR(c[2], t.height(c[0], c[1]), 1e-10);
    }
    for (const auto v : m.vertices()) {
        EXPECT_GT(m.normal(v)[2], 0.0);
        EXPECT_NEAR(m.normal(v).norm(), 1.0, 1e-12);
    }
    // The apex vertex: by symmetry its normal is straight up.
    const auto apex = OpenMesh::VertexHandle(7 * 21 + 10);
    EXPECT_NEAR(m.point(apex)[0], 0.0, 1e-12);
    EXPECT_NEAR(m.point(apex)[1], 0.0, 1e-12);
    EXPECT_NEAR(m.normal(apex)[2], 1.0, 1e-12);
}

TEST(TerrainIndex, SurvivesMovingTheTerrain)
{
    Terrain a = ridge_terrain();
    ASSERT_TRUE(a.intersect_ray({400.0, 0.0, 100.0}, {0.0, 0.0, -1.0}));  // builds the index
    Terrain b = std::move(a);
    const auto hit = b.intersect_ray({405.0, 0.0, 100.0}, {0.0, 0.0, -1.0});
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->point.z, ridge_mesh_height(405.0), 1e-9);
}
