// `kiri author` on fog placed by the terrain, as a user runs it: the maps, their
// determinism, the valley mask a user can accept and feed back, one-line errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cli/kiri_runner.hpp"
#include "temp_path.hpp"

namespace fs = std::filesystem;
using kiri::test::read_all;
using kiri::test::run_kiri;
using kiri::test::shell_quote;

namespace {

const fs::path scenes = fs::path(KIRI_DATA_DIR) / "scenes";
const std::string dem = (fs::path(KIRI_DATA_DIR) / "terrains/jacksboro_fault_dem.tif").string();

fs::path write_scene(const std::string& name, const std::string& fog)
{
    const fs::path p = kiri::test::temp_path(name);
    std::ofstream(p) << R"({"terrain": {"path": ")" + dem + R"(", "exaggeration": 1.5}, "fog": )" + fog + "}";
    return p;
}

const char* const kMaps[] = {"fog_top.tif", "fog_bottom.tif", "fog_thickness.tif", "fog_mask.png", "flood_level.tif"};

}  // namespace

TEST(PlacementCli, FillSceneWritesIdenticalMapsTwice)
{
    const fs::path a = kiri::test::temp_path("fill_a"), b = kiri::test::temp_path("fill_b");
    const std::string scene = (scenes / "jacksboro_fill.json").string();
    const auto ra = run_kiri("author " + scene + " -o " + a.string());
    ASSERT_EQ(ra.exit_code, 0) << ra.err;
    EXPECT_NE(ra.out.find("fog placed by the terrain:"), std::string::npos);
    ASSERT_EQ(run_kiri("author " + scene + " -o " + b.string()).exit_code, 0);
    for (const char* name : kMaps) {
        const std::string first = read_all(a / name);
        EXPECT_GT(first.size(), 100u) << name;
        EXPECT_TRUE(first == read_all(b / name)) << name << " differs between two runs";
    }
    const auto report = nlohmann::json::parse(read_all(a / "report.json"));
    const auto& region = report["placement"]["regions"][0];
    EXPECT_EQ(region["top_m"].get<double>(), 580.0);
    EXPECT_EQ(region["seeds"], "points");
    EXPECT_EQ(region["max_thickness_m"].get<double>(), 580.0 - 236.0);  // the DEM's lowest cell is in the valley
    EXPECT_TRUE(region["spills"].get<bool>());
    EXPECT_NEAR(report["optics"]["visibility_m"].get<double>(), 3.912 / 0.02, 1e-9);
    EXPECT_NEAR(report["optics"]["engines"]["hdrp_fog_attenuation_distance_m"].get<double>(), 50.0, 1e-9);
    EXPECT_EQ(report["fog"]["fill"]["top"].get<double>(), 580.0);
    // The glTF export carries the optics and the engines' equivalents too (asset.extras).
    const std::string glb = read_all(a / "layers.glb");
    ASSERT_GT(glb.size(), 20u);
    std::uint32_t json_bytes = 0;
    std::memcpy(&json_bytes, glb.data() + 12, 4);
    ASSERT_LE(20u + json_bytes, glb.size());
    const auto gltf = nlohmann::json::parse(glb.substr(20, json_bytes));
    const auto& optics = gltf["asset"]["extras"]["kiri_fog_optics"];
    EXPECT_EQ(optics["extinction_per_m"].get<double>(), 0.02);
    EXPECT_NEAR(optics["hdrp_fog_attenuation_distance_m"].get<double>(), 50.0, 1e-12);
    EXPECT_NEAR(optics["godot_fog_density"].get<double>(), 0.02, 1e-15);
    EXPECT_NEAR(optics["unreal_exponential_height_fog_density"].get<double>(),
                0.02 / (0.1 * std::log(2.0) * std::log(2.0)), 1e-12);
    EXPECT_NEAR(optics["visibility_m"].get<double>(), 195.6, 1e-9);
    fs::remove_all(a);
    fs::remove_all(b);
}

TEST(PlacementCli, TheValleyMaskCanBeAcceptedAsSeeds)
{
    const fs::path out = kiri::test::temp_path("valleys_auto"), again = kiri::test::temp_path("valleys_again");
    const fs::path automatic = write_scene("valleys_auto.json", R"({"fill": {"top": 520, "seeds": "valleys"}})");
    ASSERT_EQ(run_kiri("author " + automatic.string() + " -o " + out.string()).exit_code, 0);
    ASSERT_TRUE(fs::exists(out / "valleys.png"));
    ASSERT_TRUE(fs::exists(out / "valley_index.tif"));
    // The user looks at valleys.png, keeps it, and names it as the seed mask.
    const fs::path accepted =
        write_scene("valleys_accepted.json",
                    R"({"fill": {"top": 520, "seeds": {"mask": ")" + (out / "valleys.png").string() + R"("}}})");
    const auto r = run_kiri("author " + accepted.string() + " -o " + again.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(read_all(out / "fog_mask.png") == read_all(again / "fog_mask.png"));
    EXPECT_TRUE(read_all(out / "fog_thickness.tif") == read_all(again / "fog_thickness.tif"));
    fs::remove_all(out);
    fs::remove_all(again);
    fs::remove(automatic);
    fs::remove(accepted);
}

TEST(PlacementCli, WindSceneSpillsAndIsDeterministic)
{
    const fs::path a = kiri::test::temp_path("wind_a"), b = kiri::test::temp_path("wind_b");
    const std::string scene = (scenes / "jacksboro_wind.json").string();
    ASSERT_EQ(run_kiri("author " + scene + " -o " + a.string()).exit_code, 0);
    ASSERT_EQ(run_kiri("author " + scene + " -o " + b.string()).exit_code, 0);
    EXPECT_TRUE(read_all(a / "fog_thickness.tif") == read_all(b / "fog_thickness.tif"));
    const auto flow = nlohmann::json::parse(read_all(a / "report.json"))["placement"]["flow"];
    EXPECT_GT(flow["spilled_m3"].get<double>(), 0.0);
    EXPECT_GT(flow["stream_m3"].get<double>(), 0.0);
    EXPECT_GT(flow["evaporated_m3"].get<double>(), 0.0);
    // Volume bookkeeping: what is left + what left the grid + what evaporated = what was there.
    EXPECT_NEAR((flow["volume_after_m3"].get<double>() + flow["outflow_m3"].get<double>() +
                 flow["evaporated_m3"].get<double>()) /
                    flow["volume_before_m3"].get<double>(),
                1.0, 1e-9);
    fs::remove_all(a);
    fs::remove_all(b);
}

TEST(PlacementCli, BadPlacementIsOneLineAndNoOutput)
{
    const fs::path out = kiri::test::temp_path("bad_fill");
    for (const auto& [fog, expected] :
         {std::pair<std::string, std::string>{
              R"({"fill": {"top": 200, "seeds": [[11100, 6600]]}})",
              ": /fog/fill/top: the fog top 200 m is at or below every seed (the lowest seed's ground is 340 m)"},
          {R"({"fill": {"top": 460, "seeds": [[-40000, 0]]}})",
           ": /fog/fill/seeds/0: seed (-40000, 0) lies outside the terrain"},
          {R"({"fill": {"top": 460, "seeds": "all"}, "flow": {"wind": [1, 0], "time_step": -1}})",
           ": /fog/flow/time_step: must be in (0, 86400], got -1"}}) {
        const fs::path scene = write_scene("bad_fill.json", fog);
        const auto r = run_kiri("author " + shell_quote(scene.string()) + " -o " + out.string());
        EXPECT_EQ(r.exit_code, 2) << fog;
        EXPECT_EQ(r.error_lines(), 1) << r.err;
        EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(out)) << fog;
        fs::remove(scene);
    }
}
