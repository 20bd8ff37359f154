// The same scene gives byte-identical outputs: meshes, report (its timings aside) and image.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>

#include "cli/kiri_runner.hpp"
#include "temp_path.hpp"

namespace fs = std::filesystem;
using kiri::test::read_all;
using kiri::test::run_kiri;

namespace {

std::string without_timings(const std::string& report)
{
    // "timings_s": { ... } is the only part that may change between runs.
    return std::regex_replace(report, std::regex(R"("timings_s"\s*:\s*\{[^}]*\})"), "\"timings_s\": {}");
}

TEST(Determinism, AuthorTwiceGivesIdenticalFiles)
{
    const fs::path a = kiri::test::temp_path("determinism_a"), b = kiri::test::temp_path("determinism_b");
    const std::string scene = (fs::path(KIRI_DATA_DIR) / "scenes/jacksboro_lake.json").string();
    ASSERT_EQ(run_kiri("author " + scene + " -o " + a.string() + " --formats all").exit_code, 0);
    ASSERT_EQ(run_kiri("author " + scene + " -o " + b.string() + " --formats all").exit_code, 0);
    for (const char* name :
         {"base_surface.obj", "base_surface.ply", "layers.glb", "layers.obj", "layers.ply", "particles.ply"}) {
        const std::string first = read_all(a / name);
        EXPECT_GT(first.size(), 1000u) << name;
        EXPECT_TRUE(first == read_all(b / name)) << name << " differs between two runs";
    }
    const std::string ra = read_all(a / "report.json"), rb = read_all(b / "report.json");
    EXPECT_NE(ra.find("\"timings_s\""), std::string::npos);
    EXPECT_EQ(without_timings(ra), without_timings(rb));
    fs::remove_all(a);
    fs::remove_all(b);
}

TEST(Determinism, RenderTwiceGivesIdenticalPng)
{
    const fs::path a = kiri::test::temp_path("determinism_a.png"), b = kiri::test::temp_path("determinism_b.png");
    const std::string scene = (fs::path(KIRI_DATA_DIR) / "scenes/jacksboro.json").string();
    for (const fs::path& p : {a, b})
        ASSERT_EQ(run_kiri("render " + scene + " -o " + p.string() + " --width 200 --height 120").exit_code, 0);
    EXPECT_TRUE(read_all(a) == read_all(b));
    fs::remove(a);
    fs::remove(b);
}

}  // namespace
