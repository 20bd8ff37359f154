// render::compare_frames and its error map (fog_error.hpp) on frames whose errors are known
// exactly: no GL, the reference and the frames written by hand.
#include <gtest/gtest.h>

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

}  // namespace
