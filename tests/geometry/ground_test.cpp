// The ground every renderer draws (kiri/geometry/terrain/ground.hpp): the DEM inside, the
// surround beyond its edge against closed forms, the sea.
#include "kiri/geometry/terrain/ground.hpp"

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "kiri/geometry/terrain/terrain.hpp"

namespace {

using kiri::geometry::Ground;
using kiri::geometry::Heightfield;

// 11 x 11 samples, 100 m apart, over [-500, 500]^2, heights z(x, y).
template <class F>
Heightfield grid(F&& z)
{
    Heightfield hf;
    hf.nx = hf.ny = 11;
    hf.dx = hf.dy = 100.0;
    hf.x0 = hf.y0 = -500.0;
    for (int j = 0; j < hf.ny; ++j)
        for (int i = 0; i < hf.nx; ++i)
            hf.z.push_back(z(hf.x_of(i), hf.y_of(j)));
    hf.valid.assign(hf.z.size(), 1);
    return hf;
}

double smoothstep(double t) { return t * t * (3.0 - 2.0 * t); }

TEST(Ground, EqualsTheDemInsideTheGrid)
{
    const Heightfield hf = grid([](double x, double y) { return 300.0 + 0.2 * x + 0.05 * x * y / 100.0; });
    const kiri::geometry::Terrain terrain(hf);
    const Ground ground(hf);
    EXPECT_FALSE(ground.sea_level().has_value());
    for (double x = -500.0; x <= 500.0; x += 37.0)
        for (double y = -500.0; y <= 500.0; y += 41.0) {
            EXPECT_EQ(ground.height(x, y), terrain.height(x, y)) << x << " " << y;
            const glm::dvec3 a = ground.normal(x, y), b = terrain.normal(x, y);
            EXPECT_NEAR(glm::length(a - b), 0.0, 1e-15);
        }
}

TEST(Ground, TheSurroundEasesTheEdgesMeanToTheBase)
{
    // z = 1000 + a y: the west edge is a line, whose mean over a window is its centre's height;
    // the border's median is 1000 (13 samples at -500 a, 13 at 500 a, two of each height between).
    const double a = 0.3;
    const Heightfield hf = grid([a](double, double y) { return 1000.0 + a * y; });
    const Ground ground(hf);
    EXPECT_EQ(ground.base(), 1000.0);
    EXPECT_EQ(ground.ease(), 250.0);  // a quarter of the 1000 m side
    // West of the edge at y = 100, 125 m out: half way through the easing.
    EXPECT_NEAR(ground.height(-625.0, 100.0), 1000.0 + 100.0 * a * (1.0 - smoothstep(0.5)), 1e-12);
    // Near the corner the window is clipped to the edge: [200, 500], mean 350 a.
    EXPECT_NEAR(ground.height(-700.0, 400.0), 1000.0 + 350.0 * a * (1.0 - smoothstep(0.8)), 1e-12);
    // From the ease distance on, and to the horizon: the base.
    for (double d : {250.0, 251.0, 1e4, 1e9, 1e300})
        for (const auto& [x, y] :
             {std::pair{-500.0 - d, 0.0}, std::pair{0.0, 500.0 + d}, std::pair{500.0 + d, -500.0 - d}})
            EXPECT_EQ(ground.height(x, y), 1000.0) << x << " " << y;
    // Continuous at the edge, with the edge's slope (no crease): the west and east edges are
    // level outwards (at the corners the clipped window's mean moves by at most a / 2 per metre),
    // the north edge rises a per metre out of the grid.
    for (double y = -500.0; y <= 500.0; y += 50.0) {
        const double corner = std::abs(y) == 500.0 ? 0.5 * a * 1e-3 + 1e-7 : 1e-6;
        EXPECT_NEAR(ground.height(-500.001, y), ground.height(-500.0, y), corner) << y;
        EXPECT_NEAR(ground.height(500.001, y), ground.height(500.0, y), corner) << y;
    }
    for (double x = -500.0; x <= 500.0; x += 50.0)
        EXPECT_NEAR((ground.height(x, 500.001) - ground.height(x, 500.0)) / 1e-3, a, 1e-3);  // the window mean rounds
    // Continuous around a corner: the edges' means meet on the diagonals' sides.
    EXPECT_NEAR(ground.height(-600.0, -500.0 - 1e-9), ground.height(-600.0, -500.0), 1e-6);
    EXPECT_NEAR(ground.height(-500.0 - 1e-9, -600.0), ground.height(-500.0, -600.0), 1e-6);
}

TEST(Ground, IsFiniteEverywhere)
{
    const Heightfield hf = grid([](double x, double y) { return 1000.0 * std::sin(x / 90.0) * std::cos(y / 70.0); });
    const Ground ground(hf);
    const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
    for (double x : {-inf, -1e300, -1e6, -600.0, 0.0, 733.0, 1e300, inf, nan})
        for (double y : {-inf, -1e300, -520.0, 0.0, 1e6, inf, nan}) {
            EXPECT_TRUE(std::isfinite(ground.height(x, y))) << x << " " << y;
            const glm::dvec3 n = ground.normal(x, y);
            EXPECT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && n.z > 0.0) << x << " " << y;
        }
    EXPECT_EQ(ground.height(nan, 0.0), ground.base());
}

TEST(Ground, TheSurroundsNormalIsItsSlope)
{
    const Heightfield hf = grid([](double x, double y) { return 1000.0 + 0.2 * x + 0.1 * y; });
    const Ground ground(hf);
    for (const auto& [x, y] : {std::pair{-620.0, 30.0}, std::pair{580.0, -610.0}, std::pair{100.0, 650.0}}) {
        const double h = 1e-3;
        const glm::dvec3 expected =
            glm::normalize(glm::dvec3(-(ground.height(x + h, y) - ground.height(x - h, y)) / (2 * h),
                                      -(ground.height(x, y + h) - ground.height(x, y - h)) / (2 * h), 1.0));
        EXPECT_NEAR(glm::length(ground.normal(x, y) - expected), 0.0, 2e-3) << x << " " << y;
    }
}

TEST(Ground, WithoutTheSurroundTheEdgeContinuesFlat)
{
    const Heightfield hf = grid([](double x, double) { return 1000.0 + 0.5 * x; });
    const Ground bare(hf, false);
    EXPECT_EQ(bare.height(-5000.0, 0.0), 750.0);
    EXPECT_EQ(bare.height(700.0, 900.0), 1250.0);
}

TEST(Ground, FindsTheSea)
{
    // SRTM: the sea is a flat 0 (here the south-west half), the land rises north-east.
    const Heightfield srtm = grid([](double x, double y) { return std::max(0.0, 0.1 * (x + y)); });
    ASSERT_TRUE(kiri::geometry::sea_level(srtm).has_value());
    EXPECT_EQ(*kiri::geometry::sea_level(srtm), 0.0);
    // A bathymetric grid: depths down to -1500 m under a water surface at 0.
    const Heightfield bathymetry = grid([](double x, double) { return 1.5 * x; });
    const Ground sea(bathymetry);
    ASSERT_TRUE(sea.sea_level().has_value());
    EXPECT_EQ(sea.sample(0, 5), 0.0);     // -750 m of water: its surface
    EXPECT_EQ(sea.sample(10, 5), 750.0);  // land is land
    EXPECT_EQ(sea.height(-300.0, 0.0), 0.0);
    EXPECT_TRUE(sea.is_water(sea.height(-300.0, 0.0)));
    EXPECT_FALSE(sea.is_water(sea.height(300.0, 0.0)));
    EXPECT_EQ(sea.z_min(), 0.0);
    // No sea: all land; or a depression below 0 without a flat 0 and above -500 m (the Dead Sea).
    EXPECT_FALSE(kiri::geometry::sea_level(grid([](double x, double) { return 200.0 + 0.1 * x; })).has_value());
    EXPECT_FALSE(kiri::geometry::sea_level(grid([](double x, double) { return -420.0 + 0.1 * x; })).has_value());
    EXPECT_FALSE(kiri::geometry::sea_level(grid([](double, double) { return 0.0; })).has_value());  // a plain
}

TEST(Ground, ACoastsSurroundEndsInTheSea)
{
    // Land along the east edge (up to 200 m), sea elsewhere at the border: the surround is sea
    // far out, and east of the land it slopes down into the sea before the ease distance.
    const Heightfield hf = grid([](double x, double) { return x >= 300.0 ? 200.0 * (x - 300.0) / 200.0 : 0.0; });
    const Ground ground(hf);
    ASSERT_TRUE(ground.sea_level().has_value());
    EXPECT_EQ(ground.base(), 0.0);
    EXPECT_GT(ground.height(510.0, 0.0), 100.0);
    bool reached = false;
    for (double d = 10.0; d < ground.ease(); d += 10.0) {
        const double z = ground.height(500.0 + d, 0.0);
        EXPECT_GE(z, 0.0);
        reached = reached || ground.is_water(z);
    }
    EXPECT_TRUE(reached) << "the land's surround never meets the sea";
    EXPECT_TRUE(ground.is_water(ground.height(0.0, -700.0)));
    EXPECT_TRUE(ground.is_water(ground.height(1e6, 1e6)));
}

}  // namespace
