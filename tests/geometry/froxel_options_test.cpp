// Froxel options (froxel_options.hpp): the three slice distributions and their inverses, the
// scene's "froxel" section (keys, errors, round trip, world units).
#include <gtest/gtest.h>

#include <cmath>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/volume/froxel_options.hpp"
#include "kiri/geometry/scene/scene.hpp"

using namespace kiri::geometry;

TEST(FroxelSlices, DistributionsSpanTheRangeMonotonicallyAndInvert)
{
    for (SliceDistribution d : {SliceDistribution::exponential, SliceDistribution::log2, SliceDistribution::power}) {
        FroxelOptions o;
        o.distribution = d;
        for (const auto& [a, b] : {std::pair{1.0, 30000.0}, std::pair{29.0, 31.5}, std::pair{0.5, 2.0}}) {
            EXPECT_NEAR(slice_depth(o, 0.0, a, b), a, 1e-12 * b) << to_string(d);
            EXPECT_NEAR(slice_depth(o, 1.0, a, b), b, 1e-9 * b) << to_string(d);
            double prev = a;
            for (int k = 1; k <= 64; ++k) {
                const double s = k / 64.0, depth = slice_depth(o, s, a, b);
                EXPECT_GT(depth, prev) << to_string(d);
                EXPECT_NEAR(slice_coordinate(o, depth, a, b), s, 1e-9) << to_string(d);
                prev = depth;
            }
            EXPECT_EQ(slice_coordinate(o, a - 1.0, a, b), 0.0);
            EXPECT_EQ(slice_coordinate(o, b + 1.0, a, b), 1.0);
        }
    }
}

TEST(FroxelSlices, TheDistributionsShapes)
{
    FroxelOptions o;
    // Exponential: equal ratios, d_k = near (far / near)^(k / n).
    EXPECT_NEAR(slice_depth(o, 0.5, 1.0, 10000.0), 100.0, 1e-9);
    // Power 2 (Godot): d = a + (b - a) s^2.
    o.distribution = SliceDistribution::power;
    EXPECT_NEAR(slice_depth(o, 0.5, 0.0, 1000.0), 250.0, 1e-12);
    // log2 (Unreal): linear over the first metres, logarithmic far away: its first slice is
    // close to linear slicing's over a short range and far thinner than it over a long one.
    o.distribution = SliceDistribution::log2;
    o.log2_scale = 32.0;
    EXPECT_NEAR(slice_depth(o, 1.0 / 64.0, 0.0, 2.0), 2.0 / 64.0, 1e-3);
    EXPECT_LT(slice_depth(o, 1.0 / 64.0, 0.0, 10000.0), 0.1 * 10000.0 / 64.0);
    // A thin layer at 30 m with the standard 64 exponential slices from 1 m to 1 km: the slice
    // there is several metres deep, a 2 m layer lies inside one slice.
    o.distribution = SliceDistribution::exponential;
    const double s = slice_coordinate(o, 30.0, 1.0, 1000.0);
    const double slice = slice_depth(o, s + 1.0 / 64.0, 1.0, 1000.0) - 30.0;
    EXPECT_GT(slice, 3.0);
    EXPECT_LT(slice, 4.0);
}

TEST(FroxelOptionsJson, DefaultsKeysErrorsAndRoundTrip)
{
    const Scene plain = parse_scene(R"({"terrain": {"path": "t.tif"}})", "s.json", "/d");
    EXPECT_EQ(plain.froxel.width, 160);
    EXPECT_EQ(plain.froxel.height, 90);
    EXPECT_EQ(plain.froxel.slices, 64);
    EXPECT_TRUE(plain.froxel.fog_aware);
    EXPECT_FALSE(plain.froxel.height_fog.enabled());

    const Scene s = parse_scene(R"({"terrain": {"path": "t.tif", "exaggeration": 2},
        "froxel": {"size": [80, 45, 32], "distribution": "power", "power": 3, "temporal": false,
                   "fog_aware": false, "near": 0.5, "far": 2000, "sun_steps": 4,
                   "height_fog": {"visibility": 391.2, "base": 100, "scale_height": 50}}})",
                                "s.json", "/d");
    EXPECT_EQ(s.froxel.width, 80);
    EXPECT_EQ(s.froxel.slices, 32);
    EXPECT_EQ(s.froxel.distribution, SliceDistribution::power);
    EXPECT_FALSE(s.froxel.temporal);
    EXPECT_NEAR(s.froxel.height_fog.extinction, 0.01, 1e-15);
    const FroxelOptions w = world_froxel_options(s);
    EXPECT_EQ(w.height_fog.base, 200.0);  // stretched like the terrain
    EXPECT_EQ(w.height_fog.scale_height, 100.0);

    const Scene back = parse_scene(scene_to_json(s), "again.json", "/d");
    EXPECT_EQ(back.froxel.width, 80);
    EXPECT_EQ(back.froxel.distribution, SliceDistribution::power);
    EXPECT_EQ(back.froxel.power, 3.0);
    EXPECT_EQ(back.froxel.far, 2000.0);
    EXPECT_EQ(back.froxel.sun_steps, 4);
    EXPECT_NEAR(back.froxel.height_fog.extinction, 0.01, 1e-15);

    auto error = [](const char* froxel) {
        try {
            parse_scene(std::string(R"({"terrain": {"path": "t.tif"}, "froxel": )") + froxel + "}", "s.json", "/d");
        } catch (const kiri::InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_EQ(error(R"({"slices": 3})"),
              "s.json: /froxel/slices: unknown key (expected one of: density_samples, "
              "distribution, esm_sharpness, far, fog_aware, fog_shadows, height_fog, "
              "history_weight, log2_scale, near, pixel_steps, power, "
              "shadow_map_size, size, sun_steps, sun_volume, temporal, terrain_shadows, upsample)");
    EXPECT_EQ(error(R"({"size": [160, 90]})"),
              "s.json: /froxel/size: expected an array of 3 integers [width, height, slices]");
    EXPECT_EQ(error(R"({"size": [160, 90, 1]})"), "s.json: /froxel/size/2: must be in [2, 512], got 1");
    EXPECT_EQ(error(R"({"distribution": "linear"})"),
              "s.json: /froxel/distribution: expected \"exponential\", \"log2\" or \"power\", got \"linear\"");
    EXPECT_EQ(error(R"({"near": 10, "far": 5})"),
              "s.json: /froxel/far: must be 0 (the scene's far side) or larger than near");
    EXPECT_EQ(error(R"({"history_weight": 1})"), "s.json: /froxel/history_weight: must be in [0, 0.99], got 1");
    EXPECT_EQ(error(R"({"height_fog": {"anisotropy": 1}})"),
              "s.json: /froxel/height_fog/anisotropy: must be in (-1, 1), got 1");
    EXPECT_EQ(error(R"({"height_fog": {"extinction": 0.1, "visibility": 50}})"),
              "s.json: /froxel/height_fog: give only one of extinction and visibility");
}
