// kiri-preview in scripted mode under a virtual display (xvfb-run, installed by the set-up): the
// screenshot shows terrain and fog, and the fog region is brighter and greyer than the same
// view with the fog hidden.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "cli/kiri_runner.hpp"
#include "kiri/render/image.hpp"
#include "temp_path.hpp"

namespace fs = std::filesystem;

namespace {

struct Tone {
    double luminance = 0.0, saturation = 0.0;
    int lo = 255, hi = 0;
};

// The lower left of a 960 x 540 window: terrain under the fog, away from the panel (right)
// and the timings overlay (top left).
Tone lower_left(const kiri::render::Image& image)
{
    Tone t;
    int n = 0;
    for (int y = 300; y < image.height; ++y)
        for (int x = 0; x < 500; ++x) {
            const std::uint8_t* p = &image.rgba[(std::size_t(y) * image.width + x) * 4];
            const int hi = std::max({p[0], p[1], p[2]}), lo = std::min({p[0], p[1], p[2]});
            const double l = 0.3 * p[0] + 0.6 * p[1] + 0.1 * p[2];
            t.luminance += l;
            t.saturation += hi > 0 ? double(hi - lo) / hi : 0.0;
            t.lo = std::min(t.lo, int(l));
            t.hi = std::max(t.hi, int(l));
            ++n;
        }
    t.luminance /= n;
    t.saturation /= n;
    return t;
}

kiri::render::Image screenshot(const std::string& extra)
{
    const fs::path png = kiri::test::temp_path("preview_test" + extra + ".png");
    fs::remove(png);
    const std::string scene = (fs::path(KIRI_DATA_DIR) / "scenes/jacksboro.json").string();
    const std::string command = "xvfb-run -a -s '-screen 0 1280x720x24' " + kiri::test::shell_quote(KIRI_PREVIEW) +
                                " " + scene + " --frames 3 --width 960 --height 540 --screenshot " + png.string() +
                                " " + extra + " > /dev/null 2>&1";
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    kiri::render::Image image = kiri::render::read_png(png);
    fs::remove(png);
    return image;
}

}  // namespace

TEST(KiriPreview, ScriptedScreenshotShowsTerrainAndFog)
{
    const kiri::render::Image fog = screenshot("");
    ASSERT_EQ(fog.width, 960);
    ASSERT_EQ(fog.height, 540);
    const kiri::render::Image bare = screenshot("--no-fog");
    const Tone with = lower_left(fog), without = lower_left(bare);
    EXPECT_GT(without.hi - without.lo, 60) << "the terrain view is uniform";
    EXPECT_GT(with.hi - with.lo, 30) << "the fog view is uniform";
    EXPECT_GT(with.luminance, without.luminance + 25.0) << without.luminance << " -> " << with.luminance;
    EXPECT_LT(with.saturation, 0.7 * without.saturation) << without.saturation << " -> " << with.saturation;
}

TEST(KiriPreview, BadSceneGivesOneLineAndExitTwo)
{
    const fs::path err = kiri::test::temp_path("preview_test_err.txt");
    const std::string command = kiri::test::shell_quote(KIRI_PREVIEW) + " /no/such/scene.json > /dev/null 2> " +
                                err.string();
    const int status = std::system(command.c_str());
    EXPECT_EQ(WEXITSTATUS(status), 2);
    const std::string text = kiri::test::read_all(err);
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
    EXPECT_NE(text.find("/no/such/scene.json"), std::string::npos) << text;
}
