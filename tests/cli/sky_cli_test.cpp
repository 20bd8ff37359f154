// The GL modes' linear output (`-o x.exr`: Renderer::read_radiance before the tone map),
// `--no-sky` (no ambient, a black sky without the sun's glow) and `--black-ground` (the fog's own
// light alone) as a user runs them.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "cli/kiri_runner.hpp"
#include "kiri/render/exr_image.hpp"
#include "kiri/render/image.hpp"
#include "kiri/render/tone_map.hpp"

namespace fs = std::filesystem;
using kiri::test::run_kiri;

namespace {

const std::string jacksboro = (fs::path(KIRI_DATA_DIR) / "scenes/jacksboro.json").string();
const std::string lake = (fs::path(KIRI_DATA_DIR) / "scenes/jacksboro_lake.json").string();

double sum_luminance(const kiri::render::RadianceImage& image)
{
    double sum = 0.0;
    for (std::size_t k = 0; k < image.rgba.size(); k += 4)
        sum += 0.2126 * image.rgba[k] + 0.7152 * image.rgba[k + 1] + 0.0722 * image.rgba[k + 2];
    return sum;
}

}  // namespace

TEST(KiriSky, ExrIsTheFrameBeforeTheToneMap)
{
    for (const std::string mode : {"terrain"}) {
        const fs::path png = kiri::test::temp_path("sky_cli.png"), exr = kiri::test::temp_path("sky_cli.exr");
        const std::string args = " --mode " + mode + " --width 48 --height 27";
        ASSERT_EQ(run_kiri("render " + jacksboro + " -o " + png.string() + args).exit_code, 0);
        const auto r = run_kiri("render " + jacksboro + " -o " + exr.string() + args);
        ASSERT_EQ(r.exit_code, 0) << r.err;
        const auto linear = kiri::render::read_exr(exr);
        const auto display = kiri::render::read_png(png);
        ASSERT_EQ(linear.width, 48);
        ASSERT_EQ(linear.height, 27);
        // The tone map pass (float, on the GPU) and tone_map_level (double) agree to a level.
        int same = 0, total = 0, worst = 0;
        for (std::size_t k = 0; k < display.rgba.size(); ++k) {
            if (k % 4 == 3)
                continue;
            ASSERT_TRUE(std::isfinite(linear.rgba[k]));
            const int level = kiri::render::tone_map_level(linear.rgba[k]);
            same += level == display.rgba[k];
            worst = std::max(worst, std::abs(level - int(display.rgba[k])));
            ++total;
        }
        EXPECT_GT(double(same) / total, 0.95) << mode;
        EXPECT_LE(worst, 1) << mode;
        fs::remove(png);
        fs::remove(exr);
    }
}

TEST(KiriSky, NoSkyDrawsABlackWorld)
{
    const fs::path sky = kiri::test::temp_path("sky_cli_sky.exr"), none = kiri::test::temp_path("sky_cli_none.exr");
    const std::string args = " --mode terrain --width 48 --height 27";
    ASSERT_EQ(run_kiri("render " + jacksboro + " -o " + sky.string() + args).exit_code, 0);
    const auto r = run_kiri("render " + jacksboro + " -o " + none.string() + args + " --no-sky");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto a = kiri::render::read_exr(sky), b = kiri::render::read_exr(none);
    EXPECT_GT(a.rgba[0], 0.2f);  // pixel (0, 0) sees the sky
    for (int c = 0; c < 3; ++c)
        EXPECT_EQ(b.rgba[std::size_t(c)], 0.0f);
    // The terrain keeps the sun and loses the sky's share: darker, never black everywhere.
    double sum_a = 0.0, sum_b = 0.0;
    for (std::size_t k = 0; k < a.rgba.size(); k += 4) {
        sum_a += a.rgba[k + 1];
        sum_b += b.rgba[k + 1];
    }
    EXPECT_LT(sum_b, 0.9 * sum_a);
    EXPECT_GT(sum_b, 0.1 * sum_a);
    fs::remove(sky);
    fs::remove(none);
}

TEST(KiriSky, BlackGroundLeavesTheFogsOwnLightAsTheReferenceDrawsIt)
{
    const fs::path bare = kiri::test::temp_path("sky_cli_bare.exr"), gl = kiri::test::temp_path("sky_cli_gl.exr"),
                   ref = kiri::test::temp_path("sky_cli_ref.exr");
    const std::string args = " --width 48 --height 27 --no-sky --black-ground";
    // No fog, no sky, a black ground: nothing at all.
    const auto r = run_kiri("render " + jacksboro + " -o " + bare.string() + args + " --mode terrain");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(sum_luminance(kiri::render::read_exr(bare)), 0.0);
    // The lake's fog over a black ground: the froxels' light is the reference's (measured 0.9987
    // at 160x90), and the terrain away from the fog's edges stays black (at an edge the GL frame's
    // samples cover the fog's part of the pixel, the reference's one ray may miss it).
    const std::string size = " --width 160 --height 90 --no-sky --black-ground";
    ASSERT_EQ(run_kiri("render " + lake + " -o " + gl.string() + size + " --mode froxel").exit_code, 0);
    ASSERT_EQ(run_kiri("render " + lake + " -o " + ref.string() + size + " --mode reference").exit_code, 0);
    const auto a = kiri::render::read_exr(gl), b = kiri::render::read_exr(ref);
    ASSERT_EQ(a.rgba.size(), b.rgba.size());
    const double sa = sum_luminance(a), sb = sum_luminance(b);
    ASSERT_GT(sb, 0.0);
    EXPECT_NEAR(sa / sb, 1.0, 0.02);
    int black = 0, dark = 0;
    for (int y = 1; y + 1 < 90; ++y)
        for (int x = 1; x + 1 < 160; ++x) {
            bool around = true;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    around = around && b.rgba[(std::size_t(y + dy) * 160 + x + dx) * 4 + 1] == 0.0f;
            if (!around)
                continue;
            ++black;
            dark += a.rgba[(std::size_t(y) * 160 + x) * 4 + 1] < 1e-3f;
        }
    EXPECT_GT(black, 160 * 90 / 4);
    EXPECT_GT(dark, black * 99 / 100) << dark << " of " << black;
    for (const auto& f : {bare, gl, ref})
        fs::remove(f);
}
