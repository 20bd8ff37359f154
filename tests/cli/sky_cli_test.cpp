// The GL modes' linear output (`-o x.exr`: Renderer::read_radiance before the tone map) and
// `--no-sky` (no ambient, a black sky without the sun's glow) as a user runs them.
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
