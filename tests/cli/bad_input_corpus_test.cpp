// The bad-input corpus (docs/hardening.md): broken rasters of every format kiri reads, scenes with wrong
// types, unknown keys and values outside their documented ranges, impossible footprints and
// outputs. One ctest case each; each must meet BadInput's contract: exit code 2, one line on
// stderr naming the file and the field, no output or temporary file left behind.
#include <gtest/gtest.h>

#include <gdal.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "cli/bad_input_fixture.hpp"

namespace fs = std::filesystem;
using kiri::test::run_kiri;
using kiri::test::RunResult;
using kiri::test::shell_quote;

namespace {

const fs::path jacksboro = fs::path(KIRI_DATA_DIR) / "terrains/jacksboro_fault_dem.tif";

class BadInputCorpus : public kiri::test::BadInput {
protected:
    // A scene on the bundled DEM with `extra` appended to its top-level object.
    fs::path scene_with(const std::string& extra, const std::string& terrain_extra = "") const
    {
        return file("scene.json",
                    R"({"terrain": {"path": ")" + jacksboro.string() + "\"" + terrain_extra + "}" +
                        (extra.empty() ? "" : ", " + extra) + "}");
    }
    RunResult author(const fs::path& scene) const
    {
        return run_kiri("author " + shell_quote(scene.string()) + " -o " + shell_quote(author_dir().string()));
    }
    fs::path author_dir() const { return dir_ / "authored"; }
    // Both commands users run on a scene refuse it the same way.
    void expect_scene_refused(const fs::path& scene, const std::vector<std::string>& mentions) const
    {
        std::vector<std::string> all = mentions;
        all.insert(all.begin(), scene.string());
        expect_refused(render(scene), all, out());
        expect_refused(author(scene), all, author_dir() / "report.json");
        EXPECT_FALSE(fs::exists(author_dir())) << "author created its folder for a scene it refused";
    }
    fs::path raster(const std::string& name, const char* driver, int w, int h, const std::vector<float>& values) const
    {
        // MEM dataset copied into the requested format (PNG and AAIGrid have no Create).
        GDALDatasetH mem = GDALCreate(GDALGetDriverByName("MEM"), "", w, h, 1, GDT_Float32, nullptr);
        double gt[6] = {500000.0, 30.0, 0.0, 4000000.0, 0.0, -30.0};
        GDALSetGeoTransform(mem, gt);
        GDALRasterBandH band = GDALGetRasterBand(mem, 1);
        std::vector<float> data = values;
        EXPECT_EQ(GDALRasterIO(band, GF_Write, 0, 0, w, h, data.data(), w, h, GDT_Float32, 0, 0), CE_None);
        const fs::path p = dir_ / name;
        GDALDatasetH copy =
            GDALCreateCopy(GDALGetDriverByName(driver), p.c_str(), mem, FALSE, nullptr, nullptr, nullptr);
        EXPECT_NE(copy, nullptr) << driver;
        GDALClose(copy);
        GDALClose(mem);
        return p;
    }
    std::string cut(const fs::path& p, double fraction) const
    {
        const std::string whole = kiri::test::read_all(p);
        return whole.substr(0, std::size_t(double(whole.size()) * fraction));
    }
    void expect_raster_refused(const fs::path& raster, const std::vector<std::string>& mentions) const
    {
        std::vector<std::string> all = mentions;
        all.insert(all.begin(), raster.string() + ": ");
        expect_refused(run_kiri("info " + shell_quote(raster.string())), all, out());
        expect_refused(render(scene_for(raster)), all, out());
    }
    static std::vector<float> ramp(int n)
    {
        std::vector<float> v(std::size_t(n) * n);
        for (std::size_t i = 0; i < v.size(); ++i)
            v[i] = float(100 + i % 17);
        return v;
    }
};

// ---- Point files ------------------------------------------------------------------------------

TEST_F(BadInputCorpus, TruncatedPly)
{
    const fs::path ply = file("cut.ply",
                              "ply\nformat binary_little_endian 1.0\nelement vertex 100\nproperty float x\n"
                              "property float y\nproperty float z\nend_header\n" +
                                  std::string(120, '\x01'));
    expect_refused(render(scene_for(ply)), {ply.string(), "element vertex", "truncated"}, out());
}

TEST_F(BadInputCorpus, PlyCoordinateOfTheWrongType)
{
    const fs::path ply = file("list.ply",
                              "ply\nformat ascii 1.0\nelement vertex 1\nproperty list uchar float x\n"
                              "property float y\nproperty float z\nend_header\n1 0 0 0\n");
    expect_refused(render(scene_for(ply)), {ply.string(), "property x", "list"}, out());
}

TEST_F(BadInputCorpus, PlyNaN)
{
    const fs::path ply = file("nan.ply",
                              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                              "property float z\nend_header\n0 0 1\n1 0 nan\n0 1 2\n");
    expect_refused(render(scene_for(ply)), {ply.string(), "vertex 1", "not finite"}, out());
}

TEST_F(BadInputCorpus, CsvWithoutXyzColumns)
{
    const fs::path csv = file("pts.csv", "easting,northing,height\n0,0,1\n1,0,2\n0,1,3\n");
    expect_refused(render(scene_for(csv)), {csv.string(), "line 1", "x, y, z", "easting, northing, height"}, out());
}

// ---- Rasters ---------------------------------------------------------------------------------

TEST_F(BadInputCorpus, TruncatedPng)
{
    const fs::path png = raster("whole.png", "PNG", 64, 64, ramp(64));
    const fs::path broken = file("cut.png", cut(png, 0.5));
    expect_raster_refused(broken, {});
}

TEST_F(BadInputCorpus, CorruptPngBody)
{
    std::string bytes = "\x89PNG\r\n\x1a\n";
    bytes += std::string(200, '\x55');
    expect_raster_refused(file("corrupt.png", bytes), {"format"});
}

TEST_F(BadInputCorpus, CorruptTiffHeader)
{
    std::string bytes("II*\0", 4);
    bytes += std::string("\xff\xff\xff\x7f", 4) + std::string(64, '\x01');
    expect_raster_refused(file("corrupt.tif", bytes), {});
}

TEST_F(BadInputCorpus, TruncatedAsciiGrid)
{
    const fs::path broken = file("cut.asc",
                                 "ncols 10\nnrows 10\nxllcorner 0\nyllcorner 0\ncellsize 30\n"
                                 "1 2 3 4 5 6 7 8 9 10\n1 2 3 4 5 6 7 8 9 10\n1 2 3\n");
    expect_raster_refused(broken, {});
}

TEST_F(BadInputCorpus, AsciiGridAbsurdHeaderRefusedBeforeAllocating)
{
    const fs::path huge = file("huge.asc",
                               "ncols 1000000000\nnrows 1000000000\nxllcorner 0\nyllcorner 0\n"
                               "cellsize 30\n1 2 3\n");
    // GDAL's own header check refuses it before kiri sees a size (kiri's limit, with the memory
    // it would need, is BadInput.AbsurdDimensionsRefusedBeforeAllocating).
    expect_raster_refused(huge, {"format"});
}

TEST_F(BadInputCorpus, AsciiGridAllNodata)
{
    const fs::path nodata = file("nodata.asc",
                                 "ncols 3\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 30\n"
                                 "NODATA_value -9999\n-9999 -9999 -9999\n-9999 -9999 -9999\n"
                                 "-9999 -9999 -9999\n");
    expect_raster_refused(nodata, {"nodata: every cell is nodata"});
}

TEST_F(BadInputCorpus, HgtOfTheWrongSize) { expect_raster_refused(file("N36W085.hgt", std::string(1000, '\0')), {}); }

TEST_F(BadInputCorpus, TruncatedHgt)
{
    // SRTM3 tiles hold 1201 x 1201 big-endian int16; this one stops half way.
    expect_raster_refused(file("N36W084.hgt", std::string(1201 * 600 * 2, '\x01')), {});
}

TEST_F(BadInputCorpus, AllNaNElevations)
{
    const float nan = std::numeric_limits<float>::quiet_NaN();
    expect_raster_refused(raster("nan.tif", "GTiff", 8, 8, std::vector<float>(64, nan)), {"nodata"});
}

TEST_F(BadInputCorpus, AllPlusInfElevations)
{
    const float inf = std::numeric_limits<float>::infinity();
    expect_raster_refused(raster("inf.tif", "GTiff", 8, 8, std::vector<float>(64, inf)), {"nodata"});
}

TEST_F(BadInputCorpus, AllMinusInfElevations)
{
    const float inf = std::numeric_limits<float>::infinity();
    expect_raster_refused(raster("minus_inf.tif", "GTiff", 8, 8, std::vector<float>(64, -inf)), {"nodata"});
}

TEST_F(BadInputCorpus, OneByOneRaster)
{
    // `kiri info` describes it; a terrain needs at least 2 x 2 samples.
    const fs::path one = raster("one.tif", "GTiff", 1, 1, {5.0f});
    expect_refused(render(scene_for(one)), {one.string() + ": size", "at least 2 x 2"}, out());
}

TEST_F(BadInputCorpus, FolderWhereARasterIsExpected)
{
    fs::create_directories(dir_ / "folder.tif");
    expect_raster_refused(dir_ / "folder.tif", {});
}

// ---- Scenes: types, keys, ranges ---------------------------------------------------------------

TEST_F(BadInputCorpus, SceneIsAnArray)
{
    const fs::path scene = file("array.json", "[1, 2, 3]");
    expect_scene_refused(scene, {"expected an object"});
}

TEST_F(BadInputCorpus, SceneWithoutTerrain) { expect_scene_refused(file("empty.json", "{}"), {"/terrain", "missing"}); }

TEST_F(BadInputCorpus, TerrainPathIsANumber)
{
    expect_scene_refused(file("path.json", R"({"terrain": {"path": 42}})"), {"/terrain/path"});
}

TEST_F(BadInputCorpus, ZeroExaggeration)
{
    expect_scene_refused(scene_with("", R"(, "exaggeration": 0)"), {"/terrain/exaggeration"});
}

TEST_F(BadInputCorpus, NegativeExaggeration)
{
    expect_scene_refused(scene_with("", R"(, "exaggeration": -1.5)"), {"/terrain/exaggeration"});
}

TEST_F(BadInputCorpus, ZeroImageWidth)
{
    expect_scene_refused(scene_with(R"("image": {"width": 0, "height": 100})"), {"/image/width"});
}

TEST_F(BadInputCorpus, NegativeImageHeight)
{
    expect_scene_refused(scene_with(R"("image": {"width": 100, "height": -5})"), {"/image/height"});
}

TEST_F(BadInputCorpus, CameraFieldOfViewOf180)
{
    expect_scene_refused(
        scene_with(R"("cameras": [{"name": "a", "position": [0, 0, 9000], "target": [0, 0, 0], "fov": 180}])"),
        {"/cameras/0/fov"});
}

TEST_F(BadInputCorpus, CameraPositionWithTwoNumbers)
{
    expect_scene_refused(scene_with(R"("cameras": [{"name": "a", "position": [0, 9000], "target": [0, 0, 0]}])"),
                         {"/cameras/0/position"});
}

TEST_F(BadInputCorpus, SunDirectionOfZeroLength)
{
    expect_scene_refused(scene_with(R"("sun": {"direction": [0, 0, 0]})"), {"/sun/direction"});
}

TEST_F(BadInputCorpus, ZeroPatchSize)
{
    expect_scene_refused(scene_with(R"("fog": {"patch_size": 0})"), {"/fog/patch_size"});
}

TEST_F(BadInputCorpus, NegativePatchSize)
{
    expect_scene_refused(scene_with(R"("fog": {"patch_size": -1000})"), {"/fog/patch_size"});
}

TEST_F(BadInputCorpus, ZeroTessellation)
{
    expect_scene_refused(scene_with(R"("fog": {"tessellation": {"level": 0}})"), {"/fog/tessellation/level"});
}

TEST_F(BadInputCorpus, UnknownFogMode) { expect_scene_refused(scene_with(R"("fog": {"mode": "sea"})"), {"/fog/mode"}); }

TEST_F(BadInputCorpus, LakeWithoutAltitude)
{
    expect_scene_refused(scene_with(R"("fog": {"mode": "lake"})"), {"/fog/altitude"});
}

TEST_F(BadInputCorpus, UnknownFogKey)
{
    expect_scene_refused(scene_with(R"("fog": {"density": 3})"), {"/fog/density", "unknown key"});
}

TEST_F(BadInputCorpus, ZeroLayers)
{
    expect_scene_refused(scene_with(R"("fog": {}, "layers": {"count": 0})"), {"/layers/count"});
}

TEST_F(BadInputCorpus, NegativeLayers)
{
    expect_scene_refused(scene_with(R"("fog": {}, "layers": {"count": -3})"), {"/layers/count"});
}

TEST_F(BadInputCorpus, LayerOpacityAboveOne)
{
    expect_scene_refused(scene_with(R"("fog": {}, "layers": {"opacity": 1.5})"), {"/layers/opacity"});
}

TEST_F(BadInputCorpus, UnknownLayerKey)
{
    expect_scene_refused(scene_with(R"("fog": {}, "layers": {"colour": "grey"})"), {"/layers/colour", "unknown key"});
}

TEST_F(BadInputCorpus, NumberBeyondDouble)
{
    expect_scene_refused(scene_with(R"("fog": {"offset": 1e400})"), {"malformed JSON"});
}

// ---- Footprints ---------------------------------------------------------------------------------

TEST_F(BadInputCorpus, FootprintOutsideTheTerrain)
{
    expect_scene_refused(
        scene_with(R"("fog": {"footprint": {"type": "rectangle", "min": [90000, 90000], "max": [95000, 95000]}})"),
        {"footprint"});
}

TEST_F(BadInputCorpus, SelfIntersectingFootprint)
{
    // A bow tie: edges 0-1 and 2-3 cross.
    expect_scene_refused(
        scene_with(
            R"("fog": {"footprint": {"type": "polygon", "points": [[-5000, -5000], [5000, 5000], [5000, -5000], [-5000, 5000]]}})"),
        {"/fog/footprint/points"});
}

TEST_F(BadInputCorpus, DegenerateFootprint)
{
    expect_scene_refused(
        scene_with(R"("fog": {"footprint": {"type": "polygon", "points": [[0, 0], [1000, 0], [2000, 0]]}})"),
        {"/fog/footprint/points"});
}

// ---- Commands and outputs -------------------------------------------------------------------------

TEST_F(BadInputCorpus, AuthorWithoutFogSection)
{
    const fs::path scene = scene_with("");
    expect_refused(author(scene), {scene.string(), "/fog"}, author_dir() / "report.json");
}

TEST_F(BadInputCorpus, AuthorIntoAFile)
{
    const fs::path scene = scene_with(R"("fog": {})");
    const fs::path not_a_dir = file("plain_file", "x");
    const RunResult r = run_kiri("author " + shell_quote(scene.string()) + " -o " + shell_quote(not_a_dir.string()));
    expect_refused(r, {not_a_dir.string()}, not_a_dir / "report.json");
    EXPECT_EQ(kiri::test::read_all(not_a_dir), "x");
}

TEST_F(BadInputCorpus, RenderIntoAMissingFolder)
{
    const fs::path target = dir_ / "missing" / "deeper" / "out.png";
    expect_refused(run_kiri("render " + shell_quote(scene_with("").string()) + " -o " + shell_quote(target.string())),
                   {target.string(), "does not exist"}, out());
    EXPECT_FALSE(fs::exists(dir_ / "missing"));
}

TEST_F(BadInputCorpus, ImpossibleImageSizeOption)
{
    expect_refused(run_kiri("render " + shell_quote(scene_with("").string()) + " -o " + shell_quote(out().string()) +
                            " --width 0"),
                   {"--width"}, out());
}

TEST_F(BadInputCorpus, UnknownRenderMode)
{
    expect_refused(run_kiri("render " + shell_quote(scene_with("").string()) + " -o " + shell_quote(out().string()) +
                            " --mode holograms"),
                   {"--mode"}, out());
}

TEST_F(BadInputCorpus, LayersModeWithoutFog)
{
    const fs::path scene = scene_with("");
    expect_refused(
        run_kiri("render " + shell_quote(scene.string()) + " -o " + shell_quote(out().string()) + " --mode layers"),
        {scene.string(), "/fog"}, out());
}

}  // namespace

namespace {

TEST_F(BadInputCorpus, AuthorAboveTheMemoryLimit)
{
    // 840 patches tessellated 256 x 256 with 15 layers: tens of GiB, refused before the fit.
    const fs::path scene =
        scene_with(R"("fog": {"footprint": {"type": "terrain", "margin": 1000}, "tessellation": {"level": 256}})");
    const RunResult r = author(scene);
    expect_refused(r, {scene.string(), "/layers/count", "MiB", "the limit is 16384 MiB"}, author_dir() / "report.json");
    expect_refused(render(scene), {scene.string(), "MiB"}, out());
}

}  // namespace
