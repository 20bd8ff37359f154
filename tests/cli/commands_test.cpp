// The commands as users run them on the bundled data.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "cli/kiri_runner.hpp"
#include "kiri/render/image.hpp"

namespace fs = std::filesystem;
using kiri::test::run_kiri;

TEST(KiriInfo, JacksboroGridCellsAndRange)
{
    const auto r = run_kiri("info " + (fs::path(KIRI_DATA_DIR) / "terrains/jacksboro_fault_dem.tif").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("403 x 344 cells"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("236.00 .. 1076.00 m"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("nodata:     0 cells"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("74.5"), std::string::npos) << r.out;
}

TEST(KiriVersion, PrintsVersion)
{
    const auto r = run_kiri("--version");
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_NE(r.out.find("kiri 0.1.0"), std::string::npos);
}

TEST(KiriRender, DefaultSceneWritesAPictureAndPrintsItsPath)
{
    const fs::path out = fs::temp_directory_path() / "kiri_commands_test_default.png";
    fs::remove(out);
    const auto r = run_kiri("render " + (fs::path(KIRI_DATA_DIR) / "scenes/jacksboro.json").string() + " -o " +
                            out.string() + " --width 160 --height 90");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, out.string() + "\n");
    const kiri::render::Image image = kiri::render::read_png(out);
    EXPECT_EQ(image.width, 160);
    EXPECT_EQ(image.height, 90);
    // Terrain and sky: the picture is far from uniform, and its lower half (the terrain) is
    // darker and greener than its top rows (the sky).
    double top = 0.0, bottom = 0.0;
    int lo = 255, hi = 0;
    for (int y = 0; y < 90; ++y)
        for (int x = 0; x < 160; ++x) {
            const std::uint8_t* p = &image.rgba[(std::size_t(y) * 160 + x) * 4];
            const int l = (p[0] * 3 + p[1] * 6 + p[2]) / 10;
            lo = std::min(lo, l);
            hi = std::max(hi, l);
            (y < 10 ? top : bottom) += (y < 10 || y >= 60) ? l : 0;
        }
    EXPECT_GT(hi - lo, 80);
    EXPECT_GT(top / (10 * 160), bottom / (30 * 160) + 20);
    fs::remove(out);
}
