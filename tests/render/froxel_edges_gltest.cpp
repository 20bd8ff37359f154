// The froxels' apply at pixels whose samples see two surfaces (froxel_edges.comp): a ridge's
// silhouette against the fogged valley behind it. The resolve averages the samples' colours and
// keeps one side's depth; the apply fogs each side as far as its own surface. Judged against
// the reference through each of the frame's samples there (compare_frames' SampleReference).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "render/froxel_fixture.hpp"

namespace {

using namespace kiri::test;

TEST_F(FroxelGl, APixelOnARidgeFogsEachSideAsFarAsItsOwnSurface)
{
    // Parallel valleys 400 m apart with fog 70 m deep in their floors, seen across them from
    // 2 km at 96 x 54: each ridge stands against the fogged floor of the valley behind it.
    // Measured: over the pixels whose footprint holds two surfaces 3.8 % off the reference
    // through their samples (the whole frame 1.9 %, p99 9.6 %); with one fog per pixel, at the
    // side its resolved depth lies on, 7.8 % (3.5 %, p99 24 %).
    const g::Terrain valleys = parallel_valleys(3000.0);
    const g::Medium fog = slab(-10.0, 60.0, 0.01, 3000.0);
    Camera c;
    c.position = {-1500.0, 100.0, 1300.0};
    c.target = {0.0, 100.0, 0.0};
    const int w = 96, h = 54;
    g::FroxelOptions o = small(24, 14, 32);
    o.far = 0.0;
    Renderer r;
    r.set_terrain(valleys);
    SunLight light = sun();  // its shadow map as the options set it (SceneRendering::sun)
    light.terrain_shadows = o.terrain_shadows;
    light.shadow_map_size = 4096;
    light.esm_sharpness = o.esm_sharpness;
    r.set_sun(light);
    r.set_froxel_fog(&fog, o);
    r.render(c, w, h);
    const kiri::render::RadianceImage with_fog = r.read_radiance();
    const int split = r.last_stats().froxel.edge_pixels;
    r.clear_froxel_fog();
    r.draw(c, w, h);
    const kiri::render::RadianceImage plain = r.read_radiance();
    const kiri::render::RadianceSamples samples = r.read_radiance_samples();
    ASSERT_EQ(samples.samples, 4);
    SunLight dark = light;  // the ground's sky light alone: the reference's shade dims the rest
    dark.intensity = 0.0;
    r.set_sun(dark);
    r.draw(c, w, h);
    const kiri::render::RadianceImage sky_lit = r.read_radiance();
    const kiri::render::RadianceSamples sky_lit_samples = r.read_radiance_samples();

    const g::ReferenceView view = kiri::render::reference_view(c, w, h, o.far);
    const g::FogLighting lit = lighting(light, o, &fog, valleys);
    g::ReferenceImage centre = g::render_reference_fog({&fog, o.height_fog}, &valleys.heightfield(), view, lit);
    kiri::render::SampleReference at_samples;
    at_samples.pixels = kiri::render::footprint_edges(centre);
    at_samples.reference = g::render_reference_rays({&fog, o.height_fog}, &valleys.heightfield(), view, lit,
                                                    kiri::render::sample_points(at_samples.pixels, samples));
    at_samples.without_fog = &samples;
    at_samples.without_sun = &sky_lit_samples;
    std::vector<float> error;
    const FogError e = kiri::render::compare_frames(with_fog, plain, centre, &error, &sky_lit, &at_samples);
    // Over the pixels whose footprint holds two surfaces, where the fog shows.
    double sum = 0.0;
    int judged = 0;
    for (std::size_t k : at_samples.pixels)
        if (!std::isnan(error[k])) {
            sum += std::abs(error[k]);
            ++judged;
        }
    const double edge_mean = sum / std::max(judged, 1);
    std::printf(
        "    %d pixels split by the apply, %zu of the reference's with two surfaces (%d judged): mean %.4f; "
        "whole frame %.4f (p99 %.4f) over %d pixels\n",
        split, at_samples.pixels.size(), judged, edge_mean, e.mean_relative, e.p99_relative, e.fog_pixels);
    EXPECT_GT(split, 100);
    EXPECT_GT(judged, 200);
    EXPECT_LT(edge_mean, 0.05);
    EXPECT_LT(e.mean_relative, 0.03);
    EXPECT_LT(e.p99_relative, 0.15);
}

}  // namespace
