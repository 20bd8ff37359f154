// Bad input as users bring it: each case must give exactly one line on stderr naming the file
// (and the JSON path or raster property), exit code 2, and leave no output file behind.
#include <gtest/gtest.h>

#include <gdal.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli/bad_input_fixture.hpp"
#include "cli/kiri_runner.hpp"
#include "temp_path.hpp"

namespace fs = std::filesystem;
using kiri::test::run_kiri;
using kiri::test::RunResult;
using kiri::test::shell_quote;

using kiri::test::BadInput;

namespace {

TEST_F(BadInput, MissingFile)
{
    const fs::path missing = dir_ / "no_such.tif";
    expect_refused(run_kiri("info " + missing.string()), {missing.string() + ": file: no such file"}, out());
    expect_refused(render(scene_for(missing)), {missing.string() + ": file: no such file"}, out());
    expect_refused(render(dir_ / "no_such_scene.json"), {"no_such_scene.json", "no such file"}, out());
}

TEST_F(BadInput, NotARaster)
{
    const fs::path text = file("notes.tif", "these are not elevations\n");
    expect_refused(run_kiri("info " + text.string()), {text.string() + ": format: not a raster"}, out());
    expect_refused(render(scene_for(text)), {text.string() + ": format: not a raster"}, out());
}

TEST_F(BadInput, TruncatedTiff)
{
    const std::string whole = kiri::test::read_all(fs::path(KIRI_DATA_DIR) / "terrains/jacksboro_fault_dem.tif");
    ASSERT_GT(whole.size(), 1000u);
    const fs::path cut = file("cut.tif", whole.substr(0, whole.size() / 2));
    expect_refused(render(scene_for(cut)), {cut.string() + ": data: ", "truncated"}, out());
    expect_refused(run_kiri("info " + cut.string()), {cut.string() + ": data: ", "truncated"}, out());
}

TEST_F(BadInput, ZeroSizeRaster)
{
    const fs::path empty = file("empty.tif", "");
    expect_refused(run_kiri("info " + empty.string()), {empty.string() + ": size: empty file (0 bytes)"}, out());
    expect_refused(render(scene_for(empty)), {empty.string() + ": size: empty file (0 bytes)"}, out());
}

TEST_F(BadInput, AllNodataRaster)
{
    const fs::path nodata = geotiff("nodata.tif", 8, 8, -9999.0, true);
    const RunResult r = render(scene_for(nodata));
    expect_refused(r, {nodata.string() + ": nodata: every cell is nodata"}, out());
}

TEST_F(BadInput, AbsurdDimensionsRefusedBeforeAllocating)
{
    // 200000 x 200000 float cells would need 160 GB as doubles; the sparse file is tiny.
    const fs::path huge = geotiff("huge.tif", 200000, 200000, 0.0, false, {"SPARSE_OK=TRUE", "TILED=YES"});
    ASSERT_LT(fs::file_size(huge), 50u << 20);
    expect_refused(run_kiri("info " + huge.string()), {huge.string() + ": size: 200000 x 200000", "limit"}, out());
    const RunResult r = render(scene_for(huge));
    expect_refused(r, {huge.string() + ": size: 200000 x 200000", "limit"}, out());
}

TEST_F(BadInput, MalformedJson)
{
    const fs::path scene = file("broken.json", "{\n  \"terrain\": {\"path\": \"x.tif\"\n");
    expect_refused(render(scene), {scene.string(), "malformed JSON", "line"}, out());
}

TEST_F(BadInput, WrongTypes)
{
    const fs::path dem = fs::path(KIRI_DATA_DIR) / "terrains/jacksboro_fault_dem.tif";
    const fs::path scene =
        file("types.json", R"({"terrain": {"path": ")" + dem.string() + R"("}, "sun": {"direction": "up"}})");
    expect_refused(render(scene), {scene.string(), "/sun/direction", "expected an array of 3 numbers"}, out());
}

TEST_F(BadInput, UnknownKeys)
{
    const fs::path dem = fs::path(KIRI_DATA_DIR) / "terrains/jacksboro_fault_dem.tif";
    const fs::path scene = file("keys.json", R"({"terrain": {"path": ")" + dem.string() + R"(", "exagerration": 2}})");
    expect_refused(render(scene), {scene.string(), "/terrain/exagerration", "unknown key"}, out());
}

TEST_F(BadInput, UnwritableOutputPath)
{
    const fs::path scene = fs::path(KIRI_DATA_DIR) / "scenes/jacksboro.json";
    const fs::path missing_dir = dir_ / "no_dir" / "out.png";
    RunResult r = run_kiri("render " + scene.string() + " -o " + missing_dir.string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.error_lines(), 1) << r.err;
    EXPECT_NE(r.err.find(missing_dir.string()), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("does not exist"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(missing_dir.parent_path()));
    // A folder where a file is expected.
    r = run_kiri("render " + scene.string() + " -o " + dir_.string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("is a folder"), std::string::npos) << r.err;
}

TEST_F(BadInput, AnOutputNameOfAnotherFormatIsRefused)
{
    // A PNG's bytes under a .pfm or .jpg name would pass for a file of that format.
    const fs::path scene = fs::path(KIRI_DATA_DIR) / "scenes/jacksboro.json";
    for (const char* name : {"frame.pfm", "frame.jpg", "frame"}) {
        const fs::path target = dir_ / name;
        const RunResult r = run_kiri("render " + scene.string() + " -o " + target.string() + " --width 32 --height 18");
        EXPECT_EQ(r.exit_code, 2) << name;
        EXPECT_EQ(r.error_lines(), 1) << r.err;
        EXPECT_NE(r.err.find(target.string() + ": "), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(".png"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(target)) << name;
    }
    // Either ending in any case is taken.
    const fs::path upper = dir_ / "frame.PNG";
    EXPECT_EQ(run_kiri("render " + scene.string() + " -o " + upper.string() + " --width 32 --height 18 --mode terrain")
                  .exit_code,
              0);
    EXPECT_TRUE(fs::exists(upper));
}

TEST_F(BadInput, UsageErrorsExitWithTwo)
{
    RunResult r = run_kiri("render");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.error_lines(), 1) << r.err;
    r = run_kiri("no-such-command");
    EXPECT_EQ(r.exit_code, 2);
    r = run_kiri("render " + (fs::path(KIRI_DATA_DIR) / "scenes/jacksboro.json").string() + " -o " + out().string() +
                 " --mode nonsense");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("nonsense"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out()));
}

}  // namespace
