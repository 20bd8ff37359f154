// `kiri render --mode path` (and its adaptive `--noise`), `-o x.exr` (linear radiance), `--no-sky`
// and `--black-ground` of the CPU modes (reference, path) as a user runs them: no GL needed.
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

const std::string lake = (fs::path(KIRI_DATA_DIR) / "scenes/jacksboro_lake.json").string();
const std::string jacksboro = (fs::path(KIRI_DATA_DIR) / "scenes/jacksboro.json").string();

// The share of channels whose 8-bit level is the tone map of the EXR's radiance (float
// rounding may move a level at a boundary), and the largest difference in levels.
std::pair<double, int> png_matches_exr(const kiri::render::Image& png, const kiri::render::RadianceImage& exr)
{
    int same = 0, total = 0, worst = 0;
    for (std::size_t k = 0; k < png.rgba.size(); ++k) {
        if (k % 4 == 3)
            continue;
        const int level = kiri::render::tone_map_level(exr.rgba[k]);
        same += level == png.rgba[k];
        worst = std::max(worst, std::abs(level - int(png.rgba[k])));
        ++total;
    }
    return {double(same) / total, worst};
}

}  // namespace

TEST(KiriPath, RendersDeterministicallyAndTheSeedChangesTheNoise)
{
    const fs::path a = kiri::test::temp_path("path_cli_a.png"), b = kiri::test::temp_path("path_cli_b.png"),
                   c = kiri::test::temp_path("path_cli_c.png");
    const std::string args = " --mode path --width 32 --height 18 --samples 4 --camera sun";
    const auto r = run_kiri("render " + lake + " -o " + a.string() + args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, a.string() + "\n");
    EXPECT_NE(r.err.find("4 samples per pixel"), std::string::npos) << r.err;
    ASSERT_EQ(run_kiri("render " + lake + " -o " + b.string() + args).exit_code, 0);
    ASSERT_EQ(run_kiri("render " + lake + " -o " + c.string() + args + " --seed 2").exit_code, 0);
    EXPECT_EQ(kiri::test::read_all(a), kiri::test::read_all(b));
    EXPECT_NE(kiri::test::read_all(a), kiri::test::read_all(c));
    const auto image = kiri::render::read_png(a);
    EXPECT_EQ(image.width, 32);
    EXPECT_EQ(image.height, 18);
    for (const auto& p : {a, b, c})
        fs::remove(p);
}

TEST(KiriPath, ExrHoldsTheRadianceThePngToneMaps)
{
    for (const std::string mode : {"reference", "path"}) {
        const fs::path png = kiri::test::temp_path("path_cli_linear.png"), exr = kiri::test::temp_path("path_cli.exr");
        const std::string args = " --mode " + mode + " --width 24 --height 14 --samples 2 --camera sun";
        ASSERT_EQ(run_kiri("render " + lake + " -o " + png.string() + args).exit_code, 0);
        const auto r = run_kiri("render " + lake + " -o " + exr.string() + args);
        ASSERT_EQ(r.exit_code, 0) << r.err;
        EXPECT_EQ(r.out, exr.string() + "\n");
        const auto linear = kiri::render::read_exr(exr);
        ASSERT_EQ(linear.width, 24);
        ASSERT_EQ(linear.height, 14);
        double brightest = 0.0;
        for (float v : linear.rgba) {
            ASSERT_TRUE(std::isfinite(v));
            brightest = std::max(brightest, double(v));
        }
        EXPECT_GT(brightest, 0.1) << mode;
        const auto [share, worst] = png_matches_exr(kiri::render::read_png(png), linear);
        EXPECT_GT(share, 0.99) << mode;
        EXPECT_LE(worst, 1) << mode;
        fs::remove(png);
        fs::remove(exr);
    }
}

TEST(KiriPath, NoSkyIsBlackAboveTheHorizonAndBlackGroundLeavesTheFog)
{
    // The default camera sees sky in its top row: sky.frag's colour, black with --no-sky.
    const fs::path sky = kiri::test::temp_path("path_cli_sky.exr"), none = kiri::test::temp_path("path_cli_none.exr"),
                   dark = kiri::test::temp_path("path_cli_dark.exr");
    const std::string args = " --mode reference --width 16 --height 9";
    ASSERT_EQ(run_kiri("render " + jacksboro + " -o " + sky.string() + args).exit_code, 0);
    ASSERT_EQ(run_kiri("render " + jacksboro + " -o " + none.string() + args + " --no-sky").exit_code, 0);
    ASSERT_EQ(run_kiri("render " + jacksboro + " -o " + dark.string() + args + " --no-sky --black-ground").exit_code,
              0);
    const auto a = kiri::render::read_exr(sky), b = kiri::render::read_exr(none), c = kiri::render::read_exr(dark);
    EXPECT_GT(a.rgba[0], 0.2f);  // pixel (0, 0): sky
    EXPECT_EQ(b.rgba[0], 0.0f);
    EXPECT_EQ(b.rgba[2], 0.0f);
    // Without the sky the fog is lit by the sun alone, and the ground adds nothing more.
    double sum_a = 0.0, sum_b = 0.0, sum_c = 0.0;
    for (std::size_t k = 0; k < a.rgba.size(); k += 4) {
        sum_a += a.rgba[k + 1];
        sum_b += b.rgba[k + 1];
        sum_c += c.rgba[k + 1];
        EXPECT_LE(c.rgba[k + 1], b.rgba[k + 1] + 1e-6f);
    }
    EXPECT_LT(sum_b, sum_a);
    EXPECT_LT(sum_c, sum_b);
    EXPECT_GT(sum_c, 0.0);
    for (const auto& p : {sky, none, dark})
        fs::remove(p);
}

TEST(KiriPath, BadOptionsAreOneLineAndExit2)
{
    const fs::path out = kiri::test::temp_path("path_cli_bad.png");
    const auto s = run_kiri("render " + lake + " -o " + out.string() + " --mode path --samples 0");
    EXPECT_EQ(s.exit_code, 2);
    EXPECT_EQ(s.error_lines(), 1) << s.err;
    const auto n = run_kiri("render " + lake + " -o " + out.string() + " --mode reference --noise 0.05");
    EXPECT_EQ(n.exit_code, 2);
    EXPECT_EQ(n.err, "kiri: " + lake + ": --noise: only --mode path samples adaptively\n");
    const auto m = run_kiri("render " + lake + " -o " + out.string() + " --mode path --samples 64 --max-samples 32");
    EXPECT_EQ(m.exit_code, 2);
    EXPECT_EQ(m.err, "kiri: " + lake + ": --max-samples: 32 is under --samples 64\n");
    for (const char* noise : {"-0.1", "nan", "2"}) {
        const auto q = run_kiri("render " + lake + " -o " + out.string() + " --mode path --noise " + noise);
        EXPECT_EQ(q.exit_code, 2) << noise;
        EXPECT_EQ(q.error_lines(), 1) << q.err;
    }
    EXPECT_FALSE(fs::exists(out));
}

TEST(KiriPath, NoiseTakesMorePathsWhereTheImageIsNoisy)
{
    // The lake from its sun camera at 16 paths a pixel, then adaptively up to 256: the noisy
    // blocks take more and the image's noise falls; the same seed gives the same picture.
    const fs::path plain = kiri::test::temp_path("path_cli_plain.exr"), a = kiri::test::temp_path("path_cli_a.exr"),
                   b = kiri::test::temp_path("path_cli_b.exr");
    const std::string args = " --mode path --width 32 --height 18 --samples 16 --camera sun --bounces 8";
    const auto p = run_kiri("render " + lake + " -o " + plain.string() + args);
    ASSERT_EQ(p.exit_code, 0) << p.err;
    const auto r = run_kiri("render " + lake + " -o " + a.string() + args + " --noise 0.05 --max-samples 256");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("16 to 256 samples per pixel"), std::string::npos) << r.err;
    ASSERT_EQ(run_kiri("render " + lake + " -o " + b.string() + args + " --noise 0.05 --max-samples 256").exit_code, 0);
    EXPECT_EQ(kiri::test::read_all(a), kiri::test::read_all(b));
    const auto error = [](const std::string& err) {
        const std::size_t at = err.find("seed 1: ");
        return at == std::string::npos ? 1e9 : std::stod(err.substr(at + 8));
    };
    EXPECT_LT(error(r.err), 0.5 * error(p.err)) << p.err << r.err;
    for (const auto& f : {plain, a, b})
        fs::remove(f);
}
