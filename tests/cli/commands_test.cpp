// The commands as users run them on the bundled data.
#include <gtest/gtest.h>

#include "temp_path.hpp"

#include <algorithm>
#include <filesystem>
#include <unistd.h>
#include <sstream>
#include <string>
#include <vector>

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
    const fs::path out = kiri::test::temp_path("commands_test_default.png");
    fs::remove(out);
    const auto r = run_kiri("render " + (fs::path(KIRI_DATA_DIR) / "scenes/jacksboro.json").string() + " -o " +
                            out.string() + " --width 160 --height 90 --mode terrain");
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

// The benchmark stages are compiled in with KIRI_BUILD_BENCH (tests/cli/CMakeLists.txt).
#if KIRI_BUILD_BENCH
TEST(KiriBench, EndToEndStageWritesCsvAndPlot)
{
    const fs::path dir = kiri::test::temp_path("commands_test_bench");
    fs::remove_all(dir);
    const auto r = run_kiri("bench --quick -o " + dir.string() + " --stage end_to_end");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string csv = kiri::test::read_all(dir / "end_to_end.csv");
    ASSERT_EQ(csv.rfind("stage,series,parameters,x,time_s,error_metric,error_value,items_per_s,peak_rss_mb\n", 0), 0u)
        << csv;
    // --quick renders 320x180 and 640x360: one row each, with a time and a peak memory > 0.
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 3) << csv;
    std::istringstream lines(csv);
    std::string line;
    std::getline(lines, line);
    for (const char* size : {"320x180", "640x360"}) {
        ASSERT_TRUE(std::getline(lines, line));
        EXPECT_NE(line.find(size), std::string::npos) << line;
        std::vector<std::string> cols;
        std::string col;
        for (std::istringstream cells(line); std::getline(cells, col, ',');)
            cols.push_back(col);
        ASSERT_EQ(cols.size(), 9u) << line;
        EXPECT_GT(std::stod(cols[4]), 0.0) << line;   // time_s
        EXPECT_GT(std::stod(cols[8]), 10.0) << line;  // peak_rss_mb of the child: a GL context and a DEM
    }
    const std::string png = kiri::test::read_all(dir / "end_to_end.png");
    EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
    EXPECT_NE(r.out.find("kiri render (cold start)"), std::string::npos) << r.out;
    fs::remove_all(dir);
}

TEST(KiriBench, UnknownStageIsAUsageError)
{
    const fs::path dir = kiri::test::temp_path("commands_test_bench_bad");
    fs::remove_all(dir);
    const auto r = run_kiri("bench -o " + dir.string() + " --stage nonsense");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err, "kiri: --stage: unknown stage \"nonsense\" (see kiri bench --list)\n");
    EXPECT_FALSE(fs::exists(dir));
}
#else
TEST(KiriBench, BuiltWithoutStagesSaysSo)
{
    const fs::path dir = kiri::test::temp_path("commands_test_bench_none");
    fs::remove_all(dir);
    const auto r = run_kiri("bench --quick -o " + dir.string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err, "kiri: bench: this kiri was built without its benchmark stages (KIRI_BUILD_BENCH=OFF)\n");
    EXPECT_FALSE(fs::exists(dir));
}
#endif
