// Automatic seeding: the cold-air-pool index finds the troughs and ignores units.
#include <gtest/gtest.h>

#include <cmath>

#include "fog_test_terrains.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/placement/valley_analysis.hpp"

using namespace kiri::geometry;
using kiri::test::make_heightfield;

TEST(ValleyAnalysis, TroughsOfACorrugationAreTheValleys)
{
    // Valleys along y every 1000 m (troughs at x = 0, +-1000, ...).
    const Heightfield hf = make_heightfield(161, 81, 25.0, -2000.0, -1000.0, [](double x, double) {
        return 300.0 - 100.0 * std::cos(2.0 * M_PI * x / 1000.0);
    });
    ValleyOptions o;
    o.radii = {250.0};
    o.threshold = 0.5;
    const ValleyMap v = analyse_valleys(hf, o);
    for (int i = 8; i < hf.nx - 8; ++i) {
        const double x = hf.x_of(i);
        const double phase = std::cos(2.0 * M_PI * x / 1000.0);
        const std::size_t k = std::size_t(40) * hf.nx + i;
        if (phase > 0.8) {
            EXPECT_EQ(v.mask[k], 1) << x;  // trough
        }
        if (phase < 0.0) {
            EXPECT_EQ(v.mask[k], 0) << x;  // flanks and crests
        }
    }
    EXPECT_GT(v.cells, 0u);
}

TEST(ValleyAnalysis, TheIndexIgnoresScaleAndOffsetOfTheHeights)
{
    const Heightfield a = make_heightfield(60, 50, 30.0, 0.0, 0.0, kiri::test::hills);
    Heightfield b = a;
    for (double& z : b.z)
        z = 1.5 * z + 1234.0;  // an exaggeration and a datum
    const ValleyMap va = analyse_valleys(a, {}), vb = analyse_valleys(b, {});
    ASSERT_EQ(va.radii, vb.radii);
    for (std::size_t k = 0; k < va.index.size(); ++k)
        ASSERT_NEAR(va.index[k], vb.index[k], 1e-9);
    EXPECT_EQ(va.mask, vb.mask);
}

TEST(ValleyAnalysis, DefaultRadiiAndRefusals)
{
    const Heightfield hf = make_heightfield(100, 100, 10.0, 0.0, 0.0, kiri::test::hills);
    const ValleyMap v = analyse_valleys(hf, {});
    ASSERT_EQ(v.radii.size(), 3u);
    EXPECT_DOUBLE_EQ(v.radii[0], 40.0);
    EXPECT_DOUBLE_EQ(v.radii[1], 160.0);
    EXPECT_DOUBLE_EQ(v.radii[2], 0.25 * 990.0);  // capped at a quarter of the extent
    ValleyOptions bad;
    bad.radii = {100.0, -1.0};
    try {
        analyse_valleys(hf, bad, "s.json");
        FAIL();
    } catch (const kiri::InputError& e) {
        EXPECT_EQ(e.field(), "valleys/radii/1");
    }
}
