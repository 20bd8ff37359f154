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

}  // namespace
