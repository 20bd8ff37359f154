// The commands as users run them on the bundled data.
#include <gtest/gtest.h>

#include "temp_path.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <unistd.h>
#include <sstream>
#include <string>
#include <vector>

#include "cli/kiri_runner.hpp"
#include "cli/reference_judge.hpp"
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
    // The default scene in its default mode (combined), small: its fog against the CPU reference
    // of the same fog, the Medium and the height fog (reference_judge.hpp).
    const std::string scene = (fs::path(KIRI_DATA_DIR) / "scenes/jacksboro.json").string();
    const fs::path out = kiri::test::temp_path("commands_test_default.exr");
    fs::remove(out);
    const auto r = run_kiri("render " + scene + " -o " + out.string() + " --width 64 --height 36");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, out.string() + "\n");
    EXPECT_NE(r.err.find("64x36, mode combined"), std::string::npos) << r.err;
    const kiri::render::RadianceImage fog = kiri::render::read_exr(out);
    fs::remove(out);
    EXPECT_EQ(fog.width, 64);
    EXPECT_EQ(fog.height, 36);
    const kiri::render::RadianceImage bare = kiri::test::render_radiance(scene, "terrain", "--width 64 --height 36");
    const kiri::geometry::ReferenceImage reference = kiri::test::scene_reference(scene, "", 64, 36, true);
    // Measured 0.105, grey veils at least 0.239. (Both frames draw the terrain in the sun's one
    // shadow map.)
    const double bound = 0.125;
    kiri::test::expect_fog_agrees("combined", fog, bare, reference, 64 * 36 / 3, bound);
}

// A scene draws the same picture every run. The ground's shade carried on past a fog's shore
// (ground_shade.comp, phase 3) was written by each marked vertex's block of the fine map from the
// runs within its own cells, so a texel two blocks share took the value of whichever wrote last:
// the lake's picture differed at 30 to 70 pixels from one run to the next (every run at 160x90).
TEST(KiriRender, TheLakeIsTheSamePictureFromRunToRun)
{
    const std::string scene = (fs::path(KIRI_DATA_DIR) / "scenes/jacksboro_lake.json").string();
    const kiri::render::RadianceImage first = kiri::test::render_radiance(scene, "froxel", "--width 160 --height 90");
    const kiri::render::RadianceImage second = kiri::test::render_radiance(scene, "froxel", "--width 160 --height 90");
    ASSERT_EQ(first.rgba.size(), second.rgba.size());
    ASSERT_FALSE(first.rgba.empty());
    std::size_t differ = 0;
    for (std::size_t k = 0; k < first.rgba.size(); ++k)
        differ += first.rgba[k] != second.rgba[k] ? 1 : 0;
    EXPECT_EQ(differ, 0u) << "values that differ between two runs";
}

// The benchmark stages are compiled in with KIRI_BUILD_BENCH (tests/cli/CMakeLists.txt).
#if KIRI_BUILD_BENCH
// A bench CSV row's cells (none of them holds a comma).
std::vector<std::string> csv_cells(const std::string& line)
{
    std::vector<std::string> cols;
    std::string col;
    for (std::istringstream cells(line); std::getline(cells, col, ',');)
        cols.push_back(col);
    return cols;
}

TEST(KiriBench, EndToEndStageWritesCsvAndPlot)
{
    const fs::path dir = kiri::test::temp_path("commands_test_bench");
    fs::remove_all(dir);
    const auto r = run_kiri("bench --quick -o " + dir.string() + " --stage end_to_end");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string csv = kiri::test::read_all(dir / "end_to_end.csv");
    ASSERT_EQ(csv.rfind("stage,series,parameters,x,time_s,error_metric,error_value,items_per_s,peak_rss_mb\n", 0), 0u)
        << csv;
    // --quick renders 320x180 and 640x360: one row each, with a time, an error and a peak memory.
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 3) << csv;
    std::istringstream lines(csv);
    std::string line;
    std::getline(lines, line);
    for (const char* size : {"320x180", "640x360"}) {
        ASSERT_TRUE(std::getline(lines, line));
        EXPECT_NE(line.find(size), std::string::npos) << line;
        const std::vector<std::string> cols = csv_cells(line);
        ASSERT_EQ(cols.size(), 9u) << line;
        EXPECT_GT(std::stod(cols[4]), 0.0) << line;  // time_s
        // The picture's error against the CPU reference, judged at 64 x 36: measured 0.105 at
        // both sizes (DefaultSceneWritesAPicture's 0.104 from the linear radiance).
        EXPECT_EQ(cols[5], "\"mean relative luminance error vs reference (64x36)\"") << line;
        EXPECT_GT(std::stod(cols[6]), 0.01) << line;
        EXPECT_LT(std::stod(cols[6]), 0.125) << line;
        EXPECT_GT(std::stod(cols[8]), 10.0) << line;  // peak_rss_mb of the child: a GL context and a DEM
    }
    const std::string png = kiri::test::read_all(dir / "end_to_end.png");
    EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
    EXPECT_NE(r.out.find("kiri render (cold start)"), std::string::npos) << r.out;
    fs::remove_all(dir);
}

// `--view` keeps the views stage to the views named: the canyon written as a bare DEM (every key
// derived), judged against the CPU reference in every mode.
TEST(KiriBench, ViewsStageJudgesTheViewsNamed)
{
    const fs::path dir = kiri::test::temp_path("commands_test_bench_views");
    fs::remove_all(dir);
    const auto r = run_kiri("bench --quick -o " + dir.string() + " --stage views --view canyon/derived");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string csv = kiri::test::read_all(dir / "views.csv");
    std::istringstream lines(csv);
    std::string line;
    std::getline(lines, line);
    std::vector<std::string> modes;
    while (std::getline(lines, line)) {
        const std::vector<std::string> cols = csv_cells(line);
        ASSERT_EQ(cols.size(), 9u) << line;
        EXPECT_EQ(cols[2], "\"canyon/derived\"") << line;
        modes.push_back(cols[1]);
        // Measured 0.64 % (layers), 2.11 % (particles), 0.40 % (froxels), 0.64 % (combined) on
        // 2026-12-04; the particles 1.18 % since they match the Medium (2026-12-07), 0.79 % since
        // a small still draws them at each sample, lit by the Medium's light (their bound 1.3
        // times that: 1.18 % fails it). Each renderer's light 10 % too bright fails its bound
        // (docs/tests.md).
        const bool particles = cols[1] == "\"particles\"";
        const double measured = cols[1] == "\"layers\"" ? 0.0064
            : particles                                 ? 0.0079
            : cols[1] == "\"froxel\""                   ? 0.0040
                                                        : 0.0064;
        EXPECT_GT(std::stod(cols[6]), 0.001) << line;
        EXPECT_LT(std::stod(cols[6]), (particles ? 1.3 : 1.5) * measured) << line;
    }
    EXPECT_EQ(modes, (std::vector<std::string>{"\"layers\"", "\"particles\"", "\"froxel\"", "\"combined\""}));
    const std::string md = kiri::test::read_all(dir / "views.md");
    EXPECT_EQ(std::count(md.begin(), md.end(), '\n'), 7) << md;  // its header, one row and the worst
    fs::remove_all(dir);
}

// The bundled lake made dense (10 m of visibility): its light comes from a sunlit skin a few
// metres deep along rays that graze its top. Measured 2026-12-05: the froxels 1.73 % (3.25 %
// with a march's light taken at every fourth step where tau_sun grows by several between them,
// 6.52 % before the skin was integrated over each step), the layers 11.7 % (18.0 % lit at each
// slab's middle), combined 1.89 %.
TEST(KiriBench, TheDenseLakeIsLitAlongItsSunlitSkin)
{
    const fs::path dir = kiri::test::temp_path("commands_test_bench_dense_lake");
    fs::remove_all(dir);
    const auto r = run_kiri("bench --quick -o " + dir.string() + " --stage views --view lake_dense");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::istringstream lines(kiri::test::read_all(dir / "views.csv"));
    std::string line;
    std::getline(lines, line);
    int judged = 0;
    while (std::getline(lines, line)) {
        const std::vector<std::string> cols = csv_cells(line);
        ASSERT_EQ(cols.size(), 9u) << line;
        EXPECT_EQ(cols[2], "\"jacksboro_lake_dense/default\"") << line;
        const double error = std::stod(cols[6]);
        EXPECT_GT(error, 0.001) << line;
        if (cols[1] == "\"froxel\"" || cols[1] == "\"combined\"") {
            EXPECT_LT(error, 0.023) << line;
            ++judged;
        } else if (cols[1] == "\"layers\"") {
            EXPECT_LT(error, 0.14) << line;
            ++judged;
        }
    }
    EXPECT_EQ(judged, 3);
    // And combined's p99 (views.md's last column, "mean / p99 %"): the shores' and the hills'
    // shadows' pixels, where a sample's fog or its sunlit skin differs from the centre's. 9.3 %
    // since the samples split by their fog's light, the ground's shade ends at the shore and the
    // fog before a far shore is probed along the samples' rays (19.5 % before): the goal's 10 %.
    std::istringstream table(kiri::test::read_all(dir / "views.md"));
    double p99 = -1.0;
    while (std::getline(table, line))
        if (line.rfind("| jacksboro_lake_dense/default |", 0) == 0) {
            const std::size_t slash = line.rfind('/');
            ASSERT_NE(slash, std::string::npos) << line;
            p99 = std::stod(line.substr(slash + 1));
        }
    EXPECT_GT(p99, 0.0);
    EXPECT_LT(p99, 10.0) << "combined's p99 over the dense lake, in per cent";
    fs::remove_all(dir);
}

// A --view that names no view, or one without the views stage: one line, exit 2, nothing written.
TEST(KiriBench, AViewThatNamesNothingIsAUsageError)
{
    const fs::path dir = kiri::test::temp_path("commands_test_bench_no_view");
    fs::remove_all(dir);
    auto r = run_kiri("bench --quick -o " + dir.string() + " --stage views --view nonsense");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err.rfind("kiri: --view: names none of the views (jacksboro/default, ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir / "views.md"));
    EXPECT_FALSE(fs::exists(dir / "views"));
    EXPECT_FALSE(fs::exists(dir / "views.csv"));
    r = run_kiri("bench --quick -o " + dir.string() + "_other --stage terrain --view lake");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err, "kiri: --view: chooses views of the views stage, which is not run (add --stage views)\n");
    EXPECT_FALSE(fs::exists(dir.string() + "_other"));
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
