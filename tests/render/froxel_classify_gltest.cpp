// Where the fog-aware apply reads the froxel volume and where it marches each pixel's own ray
// (froxel_classify.comp): fog the slices resolve is read with one lookup, thin fog and the
// fog's edges still march, and both stay as close to the CPU reference as the march was.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "render/froxel_fixture.hpp"

namespace {

using namespace kiri::test;

struct Applied {
    Compared compared;
    kiri::render::FroxelStats stats;
};

Applied apply(const g::Terrain& ground, const g::Medium& fog, const g::FroxelOptions& o, const Camera& c, int w, int h,
              double min_depth = 0.0, double max_depth = HUGE_VAL, const SunLight& light = sun())
{
    Renderer r;
    r.set_terrain(ground);
    r.set_sun(light);
    r.set_froxel_fog(&fog, o);
    r.render(c, w, h);
    Applied a;
    a.stats = r.last_stats().froxel;
    a.compared.gpu = r.read_froxel_fog();
    const g::ReferenceView view = kiri::render::reference_view(c, w, h, o.far);
    a.compared.reference =
        g::render_reference_fog({&fog, o.height_fog}, &ground.heightfield(), view, lighting(light, o, &fog, ground));
    a.compared.error = kiri::render::compare_fog(a.compared.gpu, a.compared.reference, min_depth, max_depth);
    expect_finite(a.compared.gpu);
    std::printf("    marched %d, took their samples' mean %d of %d pixels, mean %.4f, p99 %.4f\n",
                a.stats.marched_pixels, a.stats.upsampled_pixels, a.stats.applied_pixels,
                a.compared.error.mean_relative, a.compared.error.p99_relative);
    return a;
}

// Seen from outside the Medium the classification runs only with a height fog (without one the
// pixels that could read the volume see no fog and stop at once): a faint one.
g::FroxelOptions with_faint_haze(g::FroxelOptions o)
{
    o.height_fog.extinction = 2e-5;
    o.height_fog.base = 0.0;
    o.height_fog.scale_height = 200.0;
    return o;
}

TEST_F(FroxelGl, ResolvedFogReadsTheVolume)
{
    // HomogeneousFog's view: the eye 60 m up inside a 1.5 km slab, every ray in fog from the
    // eye to the ground or the volume's end. Where the fog changes smoothly from tile to tile
    // the pixels read the volume (46 % of them measured), and the picture is closer to the
    // reference than with every pixel marching its 24 steps (0.16 % against 0.70 % measured).
    const g::Terrain ground = flat_ground();
    const g::Medium fog = slab(0.0, 1500.0, 0.003);
    Camera c;
    c.position = {0.0, -1800.0, 60.0};
    c.target = {0.0, 0.0, 0.0};
    const Applied a = apply(ground, fog, small(24, 14), c, 96, 54);
    EXPECT_EQ(a.stats.applied_pixels, 96 * 54);
    EXPECT_LT(a.stats.marched_pixels + a.stats.upsampled_pixels, 96 * 54 * 2 / 3);
    EXPECT_GT(a.compared.error.fog_pixels, 96 * 54 / 2);
    EXPECT_LT(a.compared.error.mean_relative, 0.005);
}

TEST_F(FroxelGl, SlabSeenFromAboveMarchesWhereTheLookupWouldDrift)
{
    // The same slab from 200 m above its top: over 24 x 14 tiles the slab's in-scattering
    // changes faster from tile to tile than the bilinear lookup follows (without the haze, read
    // from the volume everywhere it was 2.1 % off the reference, marched 1.1 %): the
    // classification keeps those pixels off the volume (all of them measured: 16 % march, the
    // rest take the mean of the marched samples around them).
    const g::Terrain ground = flat_ground();
    const g::Medium fog = slab(0.0, 1500.0, 0.003);
    Camera c;
    c.position = {0.0, -2500.0, 1700.0};
    c.target = {0.0, 0.0, 0.0};
    const Applied a = apply(ground, fog, with_faint_haze(small(24, 14)), c, 96, 54);
    EXPECT_GT(a.stats.marched_pixels + a.stats.upsampled_pixels, 96 * 54 * 3 / 4);
    EXPECT_GT(a.compared.error.fog_pixels, 96 * 54 / 2);
    EXPECT_LT(a.compared.error.mean_relative, 0.015);
}

TEST_F(FroxelGl, ThinLayerStillMarches)
{
    // The 2 m layer at 30 m of ThinLayerAt30Metres: seen from 5 m up its top crosses the
    // tiles at a grazing angle, where the slices cannot resolve it: those pixels march and the
    // layer keeps its error.
    const g::Terrain ground = flat_ground(1200.0, 10.0);
    const g::Medium layer = slab(0.0, 2.0, 0.05, 600.0);
    Camera c;
    c.position = {0.0, -30.0, 5.0};
    c.target = {0.0, 0.0, 0.0};
    g::FroxelOptions o = with_faint_haze(small(24, 14));
    o.far = 1000.0;
    const Applied a = apply(ground, layer, o, c, 96, 54, 25.0, 35.0);
    EXPECT_GT(a.stats.marched_pixels + a.stats.upsampled_pixels, 96 * 54 / 4);
    EXPECT_GT(a.compared.error.fog_pixels, 200);
    EXPECT_LT(a.compared.error.mean_relative, 0.02);
    EXPECT_LT(a.compared.error.p99_relative, 0.05);
}

TEST_F(FroxelGl, StandardApplyMarchesNothing)
{
    const g::Terrain ground = flat_ground();
    const g::Medium fog = slab(0.0, 1500.0, 0.003);
    Camera c;
    c.position = {0.0, -1800.0, 60.0};
    c.target = {0.0, 0.0, 0.0};
    g::FroxelOptions o = small(24, 14);
    o.fog_aware = false;
    const Applied a = apply(ground, fog, o, c, 96, 54);
    EXPECT_EQ(a.stats.applied_pixels, 96 * 54);
    EXPECT_EQ(a.stats.marched_pixels, 0);
}

// The lookup inside a slice (froxel_apply.glsl's froxel_column): 8 deep slices in a dense fog
// (0.01 per metre: a visibility of 390 m), every pixel reading the volume. Within a slice the
// transmittance falls exponentially and the in-scattered light with it; their chord between the
// slice's ends (the lookup until 2026-11-28) is 54 % off mid-slice at an optical depth of 2.
TEST_F(FroxelGl, TheLookupFollowsTheSliceInside)
{
    const g::Terrain ground = flat_ground();
    const g::Medium fog = slab(0.0, 1500.0, 0.01);
    Camera c;
    c.position = {0.0, -1800.0, 60.0};
    c.target = {0.0, 0.0, 0.0};
    g::FroxelOptions o = small(24, 14, 8);
    o.fog_aware = false;
    o.far = 3000.0;
    const Applied a = apply(ground, fog, o, c, 96, 54);
    EXPECT_EQ(a.stats.marched_pixels, 0);
    EXPECT_GT(a.compared.error.fog_pixels, 96 * 54 / 2);
    // 1.22 % and 0.0144 measured; with the chord 1.46 % and 0.0175.
    EXPECT_LT(a.compared.error.mean_relative, 0.0134);
    EXPECT_LT(a.compared.error.mean_transmittance_error, 0.016);
}

// From inside the fog every ray marches from the eye. A hill rises out of a fog 100 m deep, so
// the rays to its slopes leave the fog through its top at every distance. Steps spread over each
// ray's own length (24 of them, from the eye to its surface) put the step that straddles the
// fog's top at a different place for each pixel: the terrain's contours showed through as bands
// (the descent's view from inside, 4.4 % off the reference). Steps on one layout for every ray
// (the volume's slices, to the volume's far end, each ray stopping at its surface) end alike.
TEST_F(FroxelGl, FromInsideTheFogTheMarchDrawsNoContours)
{
    const g::Terrain hill = gaussian_hill(81, 50.0, 400.0, 700.0);
    const g::Medium fog = slab(0.0, 100.0, 0.01);
    Camera c;
    c.position = {0.0, -1900.0, 50.0};
    c.target = {0.0, 0.0, 120.0};
    const Applied a = apply(hill, fog, small(24, 14), c, 96, 54);
    EXPECT_GT(a.compared.error.fog_pixels, 96 * 54 / 2);
    std::printf("    transmittance off by %.4f on average\n", a.compared.error.mean_transmittance_error);
    // 0.48 %, p99 2.1 %, 0.0045 in transmittance measured (lit by the froxels' J 0.69 %, 3.3 %);
    // with each ray's own steps 1.45 %, 6.8 %, 0.0105.
    EXPECT_LT(a.compared.error.mean_relative, 0.010);
    EXPECT_LT(a.compared.error.p99_relative, 0.05);
    EXPECT_LT(a.compared.error.mean_transmittance_error, 0.0075);
}

// Parallel valleys 400 m apart, 160 m deep, their floors filled with fog 40 m deep: threads of
// fog about 150 m wide, seen along the valleys from 2.3 km away, the sun across them, so that the
// ridges shade part of every thread. A tile of the froxels (24 x 14 over 96 x 54 pixels) holds
// the sunlit and the shaded parts of a thread and the ridge between: a march lit by the froxels'
// J, bilinear across four tiles, mixed their light (the lake's threads from afar, 7.8 % off the
// reference); the march lights each ray at its own points.
TEST_F(FroxelGl, ThreadsOfFogInNarrowValleysKeepTheirOwnLight)
{
    const g::Terrain valleys = parallel_valleys(2000.0);
    const g::Medium fog = slab(-10.0, 40.0, 0.01);
    Camera c;
    c.position = {100.0, -2300.0, 450.0};
    c.target = {100.0, 0.0, 0.0};
    // The shadow map at about 1 m a texel: at 5 m (1024) its blur lit the shaded thirds of the
    // threads (11 % off the reference, marched at the rays' own points).
    SunLight light = sun();
    light.shadow_map_size = 4096;
    const Applied a = apply(valleys, fog, small(24, 14), c, 96, 54, 0.0, HUGE_VAL, light);
    EXPECT_GT(a.compared.error.fog_pixels, 96 * 54 / 8);
    std::printf("    in-scattered light off by %.4f on average\n", a.compared.error.mean_inscatter_relative);
    // 2.7 % and 3.1 % in the in-scattered light measured; lit by the froxels' J 21 % and 31 %.
    EXPECT_LT(a.compared.error.mean_relative, 0.04);
    EXPECT_LT(a.compared.error.mean_inscatter_relative, 0.05);
}

}  // namespace
