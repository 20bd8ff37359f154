// The height fog's free path in closed form (HeightFog::free_path) against its optical depth
// (HeightFog::optical_depth, the closed form it inverts) and against bisection on that depth:
// round trips to 1e-9 relative on steep, level, nearly level and base-crossing rays, rays that
// start where the fog has underflowed far above its base, the horizontal extent, and no free
// path where the segment holds less than the depth asked for.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>

#include "kiri/geometry/volume/height_fog.hpp"

using namespace kiri::geometry;

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

HeightFog fog()
{
    HeightFog f;
    f.extinction = 0.026;
    f.base = 420.0;
    f.scale_height = 25.0;
    return f;
}

// The oracle: bisection on the optical depth (as the path tracer found the free path before).
double bisected(const HeightFog& f, const glm::dvec3& o, const glm::dvec3& w, double t1, double depth)
{
    if (!(f.optical_depth(o, w, 0.0, t1) > depth))
        return inf;
    double lo = 0.0, hi = t1;
    for (int it = 0; it < 400 && hi - lo > 1e-13 * (1.0 + hi); ++it) {
        const double mid = 0.5 * (lo + hi);
        (f.optical_depth(o, w, 0.0, mid) < depth ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

struct Ray {
    glm::dvec3 origin, dir;
};

}  // namespace

TEST(HeightFogFreePath, InvertsTheOpticalDepth)
{
    const HeightFog f = fog();
    const std::vector<Ray> rays = {
        {{0.0, 0.0, 300.0}, {0.0, 0.0, 1.0}},                            // straight up through the base
        {{0.0, 0.0, 600.0}, {0.0, 0.0, -1.0}},                           // straight down through the base
        {{0.0, 0.0, 440.0}, glm::normalize(glm::dvec3(1.0, 0.5, 0.3))},  // up, above the base
        {{0.0, 0.0, 500.0}, glm::normalize(glm::dvec3(-1.0, 0.2, -0.1))},
        {{0.0, 0.0, 430.0}, {1.0, 0.0, 0.0}},         // level above the base
        {{0.0, 0.0, 400.0}, {0.0, 2.0, 0.0}},         // level under it (dir not unit)
        {{0.0, 0.0, 425.0}, {1.0, 0.0, 1e-9}},        // nearly level, up
        {{0.0, 0.0, 425.0}, {1.0, 0.0, -1e-12}},      // nearly level, down
        {{0.0, 0.0, 410.0}, {1.0, 0.0, 0.01}},        // crossing the base, shallow
        {{5.0, 3.0, 470.0}, {0.3, -0.2, -0.05}},      // dir not unit, crossing the base downwards
        {{0.0, 0.0, 420.0 + 3e4}, {0.1, 0.0, -1.0}},  // from where sigma underflows (1200 H up)
    };
    for (const Ray& r : rays)
        for (const double depth : {1e-6, 0.01, 0.3, 1.0, 4.0}) {
            const double t1 = 1e6;
            const double t = f.free_path(r.origin, r.dir, 0.0, t1, depth);
            if (f.optical_depth(r.origin, r.dir, 0.0, t1) < depth) {  // going up, the column holds less
                EXPECT_EQ(t, inf);
                continue;
            }
            ASSERT_TRUE(std::isfinite(t)) << r.origin.z << " " << r.dir.z << " depth " << depth;
            EXPECT_NEAR(f.optical_depth(r.origin, r.dir, 0.0, t), depth, 1e-9 * depth)
                << "from z " << r.origin.z << " along dz " << r.dir.z << ", depth " << depth;
            EXPECT_NEAR(t, bisected(f, r.origin, r.dir, t1, depth), 1e-9 * t + 1e-9)
                << "from z " << r.origin.z << " along dz " << r.dir.z << ", depth " << depth;
        }
    // A level ray under the base: t = depth / (sigma0 |dir|) exactly.
    EXPECT_DOUBLE_EQ(f.free_path({0.0, 0.0, 0.0}, {0.0, 2.0, 0.0}, 0.0, inf, 0.5), 0.5 / (0.026 * 2.0));
    // From t0 on: the same as from the point at t0.
    const glm::dvec3 o(0.0, 0.0, 380.0), w = glm::normalize(glm::dvec3(1.0, 0.0, 0.2));
    EXPECT_NEAR(f.free_path(o, w, 100.0, 1e5, 0.7), 100.0 + f.free_path(o + 100.0 * w, w, 0.0, 1e5, 0.7), 1e-9);
}

TEST(HeightFogFreePath, NoneWhereTheSegmentHoldsLess)
{
    const HeightFog f = fog();
    const glm::dvec3 up(0.0, 0.0, 1.0);
    // Up from the base the whole column holds sigma0 H = 0.65.
    EXPECT_EQ(f.free_path({0.0, 0.0, 420.0}, up, 0.0, inf, 0.66), inf);
    EXPECT_TRUE(std::isfinite(f.free_path({0.0, 0.0, 420.0}, up, 0.0, inf, 0.64)));
    // A segment ending before the depth is reached.
    const double full = f.optical_depth({0.0, 0.0, 300.0}, up, 0.0, 50.0);
    EXPECT_EQ(f.free_path({0.0, 0.0, 300.0}, up, 0.0, 50.0, full * 1.0001), inf);
    EXPECT_NEAR(f.free_path({0.0, 0.0, 300.0}, up, 0.0, 50.0, full * 0.9999), 50.0 * 0.9999, 1e-9);
    // Outside the horizontal extent there is no fog; inside it starts where the ray enters.
    HeightFog bounded = f;
    bounded.min = {100.0, -1e9};
    bounded.max = {200.0, 1e9};
    const glm::dvec3 east(1.0, 0.0, 0.0);
    EXPECT_EQ(bounded.free_path({0.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, 0.0, inf, 0.1), inf);
    EXPECT_NEAR(bounded.free_path({0.0, 0.0, 0.0}, east, 0.0, inf, 0.026 * 50.0), 150.0, 1e-9);
    EXPECT_EQ(bounded.free_path({0.0, 0.0, 0.0}, east, 0.0, inf, 0.026 * 100.0 * 1.0001), inf);
    // No fog, no depth, bad input.
    EXPECT_EQ(HeightFog{}.free_path({0.0, 0.0, 0.0}, up, 0.0, inf, 0.1), inf);
    EXPECT_EQ(f.free_path({0.0, 0.0, 0.0}, up, 0.0, inf, 0.0), inf);
    EXPECT_EQ(f.free_path({0.0, 0.0, 0.0}, glm::dvec3(0.0), 0.0, inf, 0.1), inf);
    EXPECT_EQ(f.free_path({0.0, 0.0, std::nan("")}, up, 0.0, inf, 0.1), inf);
}
