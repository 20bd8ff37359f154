// Burn-off: the sun's course, monotone thinning, thin edges and sunlit slopes first.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include <glm/geometric.hpp>

#include "fog_test_terrains.hpp"
#include "kiri/geometry/placement/burn_off.hpp"
#include "kiri/geometry/placement/fog_fill.hpp"

using namespace kiri::geometry;
using kiri::test::make_heightfield;

TEST(BurnOff, TheSunsCourse)
{
    // Equinox (declination 0 on day 81): noon elevation 90 - latitude, due south; sunrise due
    // east at 6 h.
    const glm::dvec3 noon = sun_direction(45.0, 81, 12.0);
    EXPECT_NEAR(std::asin(noon.z) * 180.0 / M_PI, 45.0, 0.5);
    EXPECT_NEAR(noon.x, 0.0, 1e-12);
    EXPECT_LT(noon.y, 0.0);
    const glm::dvec3 rise = sun_direction(45.0, 81, 6.0);
    EXPECT_NEAR(rise.z, 0.0, 0.01);
    EXPECT_NEAR(rise.x, 1.0, 0.01);
    EXPECT_NEAR(glm::length(sun_direction(36.6, 300, 9.5)), 1.0, 1e-12);
}

namespace {

// A bowl (inverted cone) filled to 300 m: thickness falls to zero at its rim.
struct Bowl {
    Heightfield hf =
        make_heightfield(81, 81, 25.0, -1000.0, -1000.0, [](double x, double y) { return 0.3 * std::hypot(x, y); });
    FogColumns dawn;
    Bowl()
    {
        FillOptions o;
        o.top = 300.0;
        o.seeds.points = {{0.0, 0.0}};
        dawn = fill_columns(hf, fill_fog(hf, o));
    }
};

BurnOffOptions at(double hour)
{
    BurnOffOptions o;
    o.time = hour;
    o.latitude = 45.0;
    o.day_of_year = 300;
    return o;
}

}  // namespace

TEST(BurnOff, ThicknessNeverGrowsWithTime)
{
    const Bowl b;
    FogColumns previous = b.dawn;
    for (double hour = 6.0; hour <= 14.0; hour += 0.5) {
        const FogColumns now = burn_off(b.hf, b.dawn, at(hour));
        for (std::size_t k = 0; k < now.mask.size(); ++k) {
            ASSERT_LE(now.thickness(k), previous.thickness(k) + 1e-12) << hour << " " << k;
            ASSERT_LE(now.mask[k], previous.mask[k]);
            if (now.mask[k]) {
                ASSERT_EQ(now.top[k], b.dawn.top[k]);  // the top stays, the base lifts
                ASSERT_GE(now.bottom[k], b.dawn.bottom[k]);
            }
        }
        previous = now;
    }
    // Before sunrise nothing has changed.
    BurnOffOptions before_dawn = at(4.0);
    before_dawn.min_thickness = 0.0;
    const FogColumns night = burn_off(b.hf, b.dawn, before_dawn);
    EXPECT_EQ(night.mask, b.dawn.mask);
    EXPECT_EQ(night.bottom, b.dawn.bottom);
}

TEST(BurnOff, ThinEdgesClearFirst)
{
    const Bowl b;
    BurnOffOptions o = at(10.0);
    o.lift_rate = 0.0;  // only the burning from below
    BurnOffReport rep;
    const FogColumns late = burn_off(b.hf, b.dawn, o, &rep);
    ASSERT_LT(rep.cells_after, rep.cells_before);
    ASSERT_GT(rep.cells_after, 0u);
    // Every cleared cell had thinner fog at dawn than every cell still in fog that faces the
    // sun the same way (same side of the bowl: compare along the ray towards the sun).
    const glm::dvec3 s = sun_direction(o.latitude, o.day_of_year, 8.0);
    const glm::dvec2 d = glm::normalize(glm::dvec2(s.x, s.y));
    double thickest_cleared = 0.0, thinnest_kept = 1e300;
    for (int step = 0; step < 40; ++step) {
        const double r = step * 25.0;
        const int i = int(std::lround((r * d.x + 1000.0) / 25.0)), j = int(std::lround((r * d.y + 1000.0) / 25.0));
        const std::size_t k = std::size_t(j) * b.hf.nx + i;
        if (!b.dawn.mask[k])
            continue;
        if (late.mask[k])
            thinnest_kept = std::min(thinnest_kept, b.dawn.thickness(k));
        else
            thickest_cleared = std::max(thickest_cleared, b.dawn.thickness(k));
    }
    EXPECT_GT(thickest_cleared, 0.0);
    EXPECT_LT(thickest_cleared, thinnest_kept);
}

TEST(BurnOff, SunlitSlopesClearBeforeShadedOnes)
{
    // A north-south valley: at 9 h the sun is in the south-east, so the west-side slope (which
    // faces east) gets it first; the same thickness on the east side (facing west) keeps fog.
    const Heightfield hf =
        make_heightfield(81, 41, 25.0, -1000.0, -500.0, [](double x, double) { return 0.5 * std::abs(x); });
    FillOptions f;
    f.top = 200.0;
    f.seeds.points = {{0.0, 0.0}};
    const FogColumns dawn = fill_columns(hf, fill_fog(hf, f));
    BurnOffOptions o = at(9.5);
    o.lift_rate = 0.0;
    const FogColumns now = burn_off(hf, dawn, o);
    int west_cleared = 0, east_cleared = 0;
    for (int i = 0; i < 40; ++i) {
        const std::size_t w = std::size_t(20) * hf.nx + i, e = std::size_t(20) * hf.nx + (80 - i);
        ASSERT_DOUBLE_EQ(dawn.thickness(w), dawn.thickness(e));
        west_cleared += dawn.mask[w] && !now.mask[w];
        east_cleared += dawn.mask[e] && !now.mask[e];
        EXPECT_LE(now.thickness(w), now.thickness(e) + 1e-9);
    }
    EXPECT_GT(west_cleared, east_cleared);
}

TEST(BurnOff, TheLiftedBaseDetachesTheFogFromTheFloor)
{
    const Bowl b;
    BurnOffOptions o = at(11.0);
    o.burn_rate = 0.0;
    BurnOffReport rep;
    const FogColumns noon = burn_off(b.hf, b.dawn, o, &rep);
    EXPECT_GT(rep.lifted_base, 0.0);
    const std::size_t centre = std::size_t(40) * b.hf.nx + 40;
    ASSERT_TRUE(noon.mask[centre]);
    EXPECT_DOUBLE_EQ(noon.bottom[centre], rep.lifted_base);  // low stratus over the floor
    EXPECT_GT(noon.bottom[centre], b.hf.z[centre]);
    // Same inputs, same bytes.
    const FogColumns again = burn_off(b.hf, b.dawn, o);
    EXPECT_EQ(std::memcmp(again.bottom.data(), noon.bottom.data(), noon.bottom.size() * sizeof(double)), 0);
}
