// render::compare_frames and its error map (fog_error.hpp) on frames whose errors are known
// exactly: no GL, the reference and the frames written by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "kiri/render/fog_error.hpp"

namespace {

using kiri::render::RadianceImage;

// A grey frame of luminance y (the luminance weights sum to 1).
RadianceImage grey(int w, int h, float y)
{
    RadianceImage image;
    image.width = w;
    image.height = h;
    image.rgba.assign(std::size_t(4 * w * h), y);
    return image;
}

TEST(FogError, SignedErrorsAreTheFramesAgainstTheReferenceComposedOverTheBackground)
{
    // Background 1.0; the reference's fog: transmittance 0.5, in-scatter 0.3, so Y_ref = 0.8.
    const int w = 3, h = 1;
    kiri::geometry::ReferenceImage ref;
    ref.width = w;
    ref.height = h;
    ref.transmittance = {0.5, 0.5, 1.0};  // the third pixel has no fog: not judged
    ref.inscatter = {glm::dvec3(0.3), glm::dvec3(0.3), glm::dvec3(0.0)};
    ref.depth.assign(3, 100.0);
    RadianceImage fog = grey(w, h, 0.8f);
    fog.rgba[4] = fog.rgba[5] = fog.rgba[6] = 0.88f;  // pixel 1: 10 % too bright
    std::vector<float> signed_error;
    const kiri::render::FogError e = kiri::render::compare_frames(fog, grey(w, h, 1.0f), ref, &signed_error);
    EXPECT_EQ(e.fog_pixels, 2);
    ASSERT_EQ(signed_error.size(), 3u);
    EXPECT_NEAR(signed_error[0], 0.0, 1e-6);
    EXPECT_NEAR(signed_error[1], 0.1, 1e-6);
    EXPECT_TRUE(std::isnan(signed_error[2]));
    EXPECT_NEAR(e.mean_relative, 0.05, 1e-6);

    // The map: white at 0, full red at +20 %, a quarter red at +5 %, grey where not judged.
    const kiri::render::Image map = kiri::render::error_map({0.0f, 0.05f, -0.4f, NAN}, 4, 1);
    const std::vector<std::uint8_t> expected = {255, 255, 255, 255, 255, 191, 191, 255,
                                                0,   0,   255, 255, 128, 128, 128, 255};
    EXPECT_EQ(map.rgba, expected);
    EXPECT_THROW(kiri::render::error_map({0.0f}, 2, 1), kiri::Error);
}

// The ground under the fog lies in its shade: the reference takes the sunlight the shade holds
// back (ReferenceImage::fog_shade) from the frame without fog before composing its fog over it.
TEST(FogError, TheFogsShadeOnTheGroundIsTakenFromTheFrameWithoutFog)
{
    // Background 1.0, of which the fog's shade takes 0.4; transmittance 0.5, in-scatter 0.3:
    // Y_ref = 0.6 * 0.5 + 0.3 = 0.6 (0.8 without the shade).
    kiri::geometry::ReferenceImage ref;
    ref.width = 2;
    ref.height = 1;
    ref.transmittance = {0.5, 0.5};
    ref.inscatter = {glm::dvec3(0.3), glm::dvec3(0.3)};
    ref.fog_shade = {glm::dvec3(0.4), glm::dvec3(0.4)};
    ref.depth.assign(2, 100.0);
    RadianceImage fog = grey(2, 1, 0.6f);
    fog.rgba[4] = fog.rgba[5] = fog.rgba[6] = 0.8f;  // pixel 1: the ground lit as if no fog were over it
    std::vector<float> signed_error;
    const kiri::render::FogError e = kiri::render::compare_frames(fog, grey(2, 1, 1.0f), ref, &signed_error);
    EXPECT_EQ(e.fog_pixels, 2);
    EXPECT_NEAR(signed_error[0], 0.0, 1e-6);
    EXPECT_NEAR(signed_error[1], 0.2 / 0.6, 1e-6);
    // A shade larger than the frame without fog (another terrain's light): the ground black, never negative.
    ref.fog_shade = {glm::dvec3(2.0), glm::dvec3(0.0)};
    EXPECT_EQ(kiri::render::compare_frames(grey(2, 1, 0.3f), grey(2, 1, 1.0f), ref, &signed_error).fog_pixels, 2);
    EXPECT_NEAR(signed_error[0], 0.0, 1e-6);
}

// With the frame without the sun, the GPU's own ground is dimmed: of its sun's part the
// reference's fog lets ground_sun through, whatever the two grounds' brightness.
TEST(FogError, WithTheFrameWithoutTheSunTheGPUsOwnGroundIsShaded)
{
    // The GPU's ground 1.0 without fog, 0.2 of it sky light: the sun's 0.8 through the fog's
    // ground_sun 0.25 gives 0.4; with transmittance 0.5 and in-scatter 0.3, Y_ref = 0.5. The
    // reference's own fog_shade (of a brighter ground) is not used.
    kiri::geometry::ReferenceImage ref;
    ref.width = 2;
    ref.height = 1;
    ref.transmittance = {0.5, 0.5};
    ref.inscatter = {glm::dvec3(0.3), glm::dvec3(0.3)};
    ref.fog_shade = {glm::dvec3(0.9), glm::dvec3(0.9)};
    ref.ground_sun = {0.25, 0.25};
    ref.depth.assign(2, 100.0);
    RadianceImage fog = grey(2, 1, 0.5f);
    fog.rgba[4] = fog.rgba[5] = fog.rgba[6] = 0.55f;  // pixel 1: 10 % too bright
    std::vector<float> signed_error;
    const RadianceImage sky_lit = grey(2, 1, 0.2f);
    const kiri::render::FogError e = kiri::render::compare_frames(fog, grey(2, 1, 1.0f), ref, &signed_error, &sky_lit);
    EXPECT_EQ(e.fog_pixels, 2);
    EXPECT_NEAR(signed_error[0], 0.0, 1e-6);
    EXPECT_NEAR(signed_error[1], 0.1, 1e-6);
    const RadianceImage wrong_size = grey(3, 1, 0.2f);
    EXPECT_THROW(kiri::render::compare_frames(fog, grey(2, 1, 1.0f), ref, nullptr, &wrong_size), kiri::Error);
}

// A pixel straddling a ridge (two samples, nothing behind them but air) and the fogged valley
// behind it (two samples): the reference is the mean over its samples, each composed over that
// sample of the frame without fog, not its centre's ray.
TEST(FogError, APixelOfTwoSurfacesIsJudgedByTheMeanOverItsSamples)
{
    kiri::geometry::ReferenceImage centre;  // its centre sees the valley: T 0.2, in-scatter 0.5
    centre.width = 2;
    centre.height = 1;
    centre.transmittance = {0.2, 0.2};
    centre.inscatter = {glm::dvec3(0.5), glm::dvec3(0.5)};
    centre.depth = {1000.0, 1000.0};
    kiri::render::RadianceSamples samples;  // pixel 0: ridge 0.4, 0.4, valley 1.0, 1.0; pixel 1 all valley
    samples.width = 2;
    samples.height = 1;
    samples.samples = 4;
    samples.offsets = {-0.125f, -0.375f, 0.375f, -0.125f, -0.375f, 0.125f, 0.125f, 0.375f};
    for (float y : {0.4f, 0.4f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f})
        samples.rgba.insert(samples.rgba.end(), {y, y, y, 1.0f});
    kiri::render::SampleReference at;
    at.pixels = {0};
    at.reference.width = 4;
    at.reference.height = 1;
    at.reference.transmittance = {1.0, 1.0, 0.2, 0.2};
    at.reference.inscatter = {glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.5), glm::dvec3(0.5)};
    at.reference.depth = {500.0, 500.0, 1000.0, 1000.0};
    at.without_fog = &samples;
    // Pixel 0: (0.4 + 0.4 + 0.7 + 0.7) / 4 = 0.55 (its centre's ray over the mean 0.7: 0.64);
    // pixel 1 by its centre: 1.0 * 0.2 + 0.5 = 0.7.
    RadianceImage without = grey(2, 1, 1.0f);
    without.rgba[0] = without.rgba[1] = without.rgba[2] = 0.7f;
    RadianceImage fog = grey(2, 1, 0.7f);
    fog.rgba[0] = fog.rgba[1] = fog.rgba[2] = 0.605f;  // 10 % too bright
    std::vector<float> signed_error;
    kiri::render::FogError e = kiri::render::compare_frames(fog, without, centre, &signed_error, nullptr, &at);
    EXPECT_EQ(e.fog_pixels, 2);
    EXPECT_NEAR(signed_error[0], 0.1, 1e-6);
    EXPECT_NEAR(signed_error[1], 0.0, 1e-6);
    // Without the samples the centre's ray judges pixel 0: 0.605 against 0.64.
    e = kiri::render::compare_frames(fog, without, centre, &signed_error);
    EXPECT_NEAR(signed_error[0], 0.605 / 0.64 - 1.0, 1e-6);
    // A reference with a ray too few for its samples, or samples of another size: an error.
    at.reference.transmittance.pop_back();
    EXPECT_THROW(kiri::render::compare_frames(fog, without, centre, nullptr, nullptr, &at), kiri::Error);

    // Where the samples lie: pixel (x, y)'s centre plus each offset, in image coordinates.
    const std::vector<glm::dvec2> points = kiri::render::sample_points({1}, samples);
    ASSERT_EQ(points.size(), 4u);
    EXPECT_DOUBLE_EQ(points[0].x, 1.375);
    EXPECT_DOUBLE_EQ(points[0].y, 0.125);
    EXPECT_DOUBLE_EQ(points[3].x, 1.625);
    EXPECT_DOUBLE_EQ(points[3].y, 0.875);
}

// A pixel's footprint holds two surfaces where its depth and its neighbours' do not lie on a
// line, or the sky meets the terrain; a smooth slope's steadily growing depths do not.
TEST(FogError, FootprintEdgesAreWhereTheDepthBendsOrTheSkyBegins)
{
    kiri::geometry::ReferenceImage ref;
    ref.width = 8;
    ref.height = 3;
    ref.depth.resize(24);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 8; ++x)  // a slope: depth linear in x; a ridge in front of it from x = 5
            ref.depth[std::size_t(y * 8 + x)] = x < 5 ? 1000.0 + 100.0 * x : 400.0;
    std::vector<std::size_t> edges = kiri::render::footprint_edges(ref);
    std::vector<std::size_t> expected;
    for (int y = 0; y < 3; ++y)
        for (int x : {4, 5})
            expected.push_back(std::size_t(y * 8 + x));
    EXPECT_EQ(edges, expected);
    // The sky above the slope's first row.
    for (int x = 0; x < 8; ++x)
        ref.depth[std::size_t(x)] = HUGE_VAL;
    edges = kiri::render::footprint_edges(ref);
    for (int x = 0; x < 8; ++x) {
        EXPECT_TRUE(std::count(edges.begin(), edges.end(), std::size_t(x)));      // the sky beside the terrain
        EXPECT_TRUE(std::count(edges.begin(), edges.end(), std::size_t(8 + x)));  // the terrain beside the sky
        EXPECT_EQ(std::count(edges.begin(), edges.end(), std::size_t(16 + x)), x == 4 || x == 5);
    }
}

TEST(FogError, FootprintEdgesAreWhereTheFogBendsOnOneSurfaceToo)
{
    // One plane (depth linear in x); the fog's transmittance falls linearly across it (the centre's
    // ray stands for the pixel), but for a thread of fog at x = 5 (a pixel's worth of it: 0.3 less),
    // and its light rises by 0.2 of the picture's over the pixels x = 2 alone.
    kiri::geometry::ReferenceImage ref;
    ref.width = 8;
    ref.height = 1;
    for (int x = 0; x < 8; ++x) {
        ref.depth.push_back(1000.0 + 100.0 * x);
        ref.transmittance.push_back(0.9 - 0.05 * x - (x == 5 ? 0.3 : 0.0));
        ref.inscatter.push_back(glm::dvec3(x == 2 ? 0.3 : 0.1));
        ref.background.push_back(glm::dvec3(1.0));
    }
    const std::vector<std::size_t> bends = {1, 2, 3, 4, 5, 6};
    EXPECT_EQ(kiri::render::footprint_edges(ref), bends);
    EXPECT_TRUE(kiri::render::footprint_edges(ref, 0.01, 0.0).empty());  // not judged: one surface
    // A gentler bend than the bound passes: the thread 0.02 deep, the light 0.02 of the picture's.
    ref.transmittance[5] = 0.9 - 0.05 * 5 - 0.02;
    ref.inscatter[2] = glm::dvec3(0.12);
    EXPECT_TRUE(kiri::render::footprint_edges(ref).empty());
}

}  // namespace
