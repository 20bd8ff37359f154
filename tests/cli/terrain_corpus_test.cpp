// Any terrain a user brings: a corpus of terrains written here as GeoTIFFs (flat, a single peak,
// a deep canyon, a coast with its sea below 0, metre and kilometre cells, geographic and
// projected, nodata borders and holes), each given to kiri as a bare DEM. The scene kiri derives
// must render with the relief visible, the fog visible but not a plate, and outputs in budget.
#include <gtest/gtest.h>

#include <gdal.h>
#include <cpl_conv.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "cli/kiri_runner.hpp"
#include "kiri/render/image.hpp"

namespace fs = std::filesystem;
using kiri::test::read_all;
using kiri::test::run_kiri;

namespace {

constexpr double nodata = -9999.0;

struct Dem {
    std::string name;
    int nx, ny;
    double cell;  // metres, or degrees when epsg is 4326
    int epsg;
    std::function<double(double x, double y)> height;  // x, y in [0, 1]; NaN: nodata
    bool relief = true;                                // false: a plain, nothing to see
};

// A GeoTIFF of the DEM, north up, with a declared nodata value where height() is NaN.
fs::path write_geotiff(const Dem& d, const fs::path& dir)
{
    GDALAllRegister();
    const fs::path p = dir / (d.name + ".tif");
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), p.c_str(), d.nx, d.ny, 1, GDT_Float32, nullptr);
    const double x0 = d.epsg == 4326 ? 10.0 : 500000.0, y0 = d.epsg == 4326 ? 46.0 : 4000000.0;
    double gt[6] = {x0, d.cell, 0.0, y0, 0.0, -d.cell};
    GDALSetGeoTransform(ds, gt);
    OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
    OSRImportFromEPSG(srs, d.epsg);
    char* wkt = nullptr;
    OSRExportToWkt(srs, &wkt);
    GDALSetProjection(ds, wkt);
    CPLFree(wkt);
    OSRDestroySpatialReference(srs);
    GDALRasterBandH band = GDALGetRasterBand(ds, 1);
    GDALSetRasterNoDataValue(band, nodata);
    std::vector<float> z(std::size_t(d.nx) * d.ny);
    for (int r = 0; r < d.ny; ++r)
        for (int c = 0; c < d.nx; ++c) {
            const double h = d.height(double(c) / (d.nx - 1), 1.0 - double(r) / (d.ny - 1));
            z[std::size_t(r) * d.nx + c] = std::isnan(h) ? float(nodata) : float(h);
        }
    EXPECT_EQ(GDALRasterIO(band, GF_Write, 0, 0, d.nx, d.ny, z.data(), d.nx, d.ny, GDT_Float32, 0, 0), CE_None);
    GDALClose(ds);
    return p;
}

double gauss(double x, double y, double cx, double cy, double s)
{
    return std::exp(-((x - cx) * (x - cx) + (y - cy) * (y - cy)) / (2.0 * s * s));
}

const double nan = std::numeric_limits<double>::quiet_NaN();

std::vector<Dem> corpus()
{
    return {
        {"flat", 60, 50, 50.0, 32633, [](double, double) { return 200.0; }, false},
        {"peak", 100, 100, 30.0, 32633,
         [](double x, double y) {
             return 300.0 + 900.0 * gauss(x, y, 0.5, 0.5, 0.16) + 30.0 * std::sin(20.0 * x) * std::cos(17.0 * y);
         }},
        {"canyon", 120, 90, 10.0, 32633,
         [](double x, double y) {
             const double axis = 0.5 + 0.1 * std::sin(6.0 * y);
             return 900.0 - 300.0 * std::exp(-(x - axis) * (x - axis) / 0.008) + 60.0 * y +
                 20.0 * std::sin(9.0 * x + 3.0 * y);
         }},
        {"coast_km_cells", 120, 91, 1000.0, 32633,
         [](double x, double y) {
             return -800.0 + 1800.0 * x + 200.0 * std::sin(8.0 * y) * x +
                 150.0 * std::sin(13.0 * x) * std::cos(7.0 * y);
         }},
        {"metre_cells", 150, 150, 1.0, 32633,
         [](double x, double y) {
             return 200.0 + 15.0 * std::sin(6.0 * x) * std::sin(5.0 * y) + 25.0 * y -
                 12.0 * std::exp(-(x - 0.5) * (x - 0.5) / 0.01);
         }},
        {"geographic_nodata_border", 95, 90, 1.0 / 120.0, 4326,
         [](double x, double y) {
             if (x < 0.06 || y < 0.05 || x > 0.95)
                 return nan;
             return 300.0 + 120.0 * std::sin(5.0 * x) * std::cos(4.0 * y) + 80.0 * y;
         }},
        {"nodata_hole", 100, 90, 90.0, 32633,
         [](double x, double y) {
             if (x < 0.08 || std::hypot(x - 0.3, y - 0.6) < 0.06)
                 return nan;
             return 300.0 + 700.0 * gauss(x, y, 0.6, 0.45, 0.15) + 40.0 * std::sin(11.0 * x) * std::sin(9.0 * y);
         }},
    };
}

double luminance(const std::uint8_t* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

// Standard deviation of the frame's luminance, in 8-bit levels.
double contrast(const kiri::render::Image& im)
{
    double sum = 0.0, sum2 = 0.0;
    const std::size_t n = std::size_t(im.width) * im.height;
    for (std::size_t k = 0; k < n; ++k) {
        const double l = luminance(&im.rgba[k * 4]);
        sum += l;
        sum2 += l * l;
    }
    const double mean = sum / double(n);
    return std::sqrt(std::max(0.0, sum2 / double(n) - mean * mean));
}

// The fraction of pixels of which the fog moves a channel by more than 4 levels (fog over a
// lit slope greys it more than it brightens it).
double changed(const kiri::render::Image& bare, const kiri::render::Image& fog)
{
    std::size_t moved = 0;
    const std::size_t n = std::size_t(bare.width) * bare.height;
    for (std::size_t k = 0; k < n; ++k) {
        int most = 0;
        for (int c = 0; c < 3; ++c)
            most = std::max(most, std::abs(int(bare.rgba[k * 4 + c]) - int(fog.rgba[k * 4 + c])));
        moved += most > 4;
    }
    return double(moved) / double(n);
}

std::uintmax_t folder_bytes(const fs::path& dir)
{
    std::uintmax_t bytes = 0;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.is_regular_file())
            bytes += e.file_size();
    return bytes;
}

class TerrainCorpus : public ::testing::TestWithParam<Dem> {
protected:
    void SetUp() override
    {
        dir_ = kiri::test::temp_path("terrain_corpus_" + GetParam().name);
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    kiri::render::Image render(const fs::path& input, const std::string& mode, const std::string& camera = "",
                               const std::string& tag = "")
    {
        const fs::path out = dir_ / (mode + camera + tag + ".png");
        const auto r =
            run_kiri("render " + input.string() + " -o " + out.string() + " --width 160 --height 90 --mode " + mode +
                     (camera.empty() ? "" : " --camera " + camera));
        EXPECT_EQ(r.exit_code, 0) << r.err;
        EXPECT_NE(r.err.find("kiri: derived: "), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find("std::"), std::string::npos) << r.err;
        return fs::exists(out) ? kiri::render::read_png(out) : kiri::render::Image{};
    }
    fs::path dir_;
};

}  // namespace

TEST_P(TerrainCorpus, TheDerivedSceneShowsReliefAndFog)
{
    const Dem& d = GetParam();
    const fs::path dem = write_geotiff(d, dir_);
    // Particles: the fog's light as the combined mode draws it, in a fraction of its time on
    // llvmpipe (the layers alone draw a thin fog fainter).
    const kiri::render::Image bare = render(dem, "terrain"), fog = render(dem, "particles");
    ASSERT_EQ(bare.rgba.size(), std::size_t(160 * 90 * 4));
    ASSERT_EQ(fog.rgba.size(), bare.rgba.size());
    if (!d.relief) {
        // A plain has no relief to show and its fog covers it all: it must only render.
        return;
    }
    // The relief's contrast is the tile's own: measured on the bare tile over the sky's grey
    // (terrain.surround false, the scene kiri derives otherwise), as the issue measured it. The
    // issue's unusable pictures had 3.7 to 10.7 levels; the bundled scene 28.7.
    const fs::path tile_scene = dir_ / "tile.json";
    {
        std::ofstream(tile_scene) << R"({"terrain": {"path": ")" << dem.filename().string()
                                  << R"(", "surround": false}, "fog": {"fill": {"seeds": "all"}}})";
    }
    EXPECT_GT(contrast(render(tile_scene, "terrain", "", "tile")), 15.0) << d.name;
    const double f = changed(bare, fog);
    // The weakest case, 61 km of gentle relief seen whole, measured 3.4 % under the octaves and
    // 2.7 % under the fitted multiple scattering (thin fog is single scattering: fainter).
    EXPECT_GT(f, 0.02) << d.name << ": the fog is invisible";
    EXPECT_LT(f, 0.8) << d.name << ": the fog is a plate";
    // The named views exist and render.
    for (const char* camera : {"valley", "inside"})
        EXPECT_EQ(render(dem, "layers", camera).rgba.size(), bare.rgba.size()) << camera;
}

TEST_P(TerrainCorpus, AuthorWritesOutputsSizedLikeTheInput)
{
    const Dem& d = GetParam();
    const fs::path dem = write_geotiff(d, dir_);
    const fs::path out = dir_ / "out";
    const auto r = run_kiri("author " + dem.string() + " -o " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(fs::exists(out / "layers.glb"));
    EXPECT_TRUE(fs::exists(out / "medium.vdb"));
    // The budget of a DEM of about 100 x 100 cells, whatever its cells measure in metres.
    EXPECT_LT(folder_bytes(out), std::uintmax_t(32) << 20) << d.name;
    EXPECT_NE(read_all(out / "report.json").find("\"derived\""), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Corpus, TerrainCorpus, ::testing::ValuesIn(corpus()),
                         [](const ::testing::TestParamInfo<Dem>& info) { return info.param.name; });

TEST(TerrainCorpusSea, TheSeaReadsAsWater)
{
    // The coast's sea (down to -950 m: a bathymetric grid) is drawn as the water's surface at 0
    // in the water's albedo (ground.hpp: 0.02, 0.045, 0.09, blue 4.5 times red), to the horizon
    // beyond the DEM's edge: dark blue pixels, 12 levels bluer than red at least (the land's
    // albedos all have less blue than red, ground.glsl) and darker than the hazed horizon
    // (145..165 levels here). Measured: 35 % of the frame; the same terrain raised 2 km above
    // the sea has none.
    const fs::path dir = kiri::test::temp_path("terrain_corpus_sea");
    fs::remove_all(dir);
    fs::create_directories(dir);
    Dem coast = corpus()[3];
    ASSERT_EQ(coast.name, "coast_km_cells");
    Dem raised = coast;
    raised.name = "raised";
    raised.height = [h = coast.height](double x, double y) { return h(x, y) + 2000.0; };
    const auto blue_share = [&](const Dem& d) {
        const fs::path dem = write_geotiff(d, dir), out = dir / (d.name + ".png");
        const auto r =
            run_kiri("render " + dem.string() + " -o " + out.string() + " --width 160 --height 90 --mode terrain");
        EXPECT_EQ(r.exit_code, 0) << r.err;
        const kiri::render::Image im = kiri::render::read_png(out);
        std::size_t blue = 0;
        for (std::size_t k = 0; k < std::size_t(im.width) * im.height; ++k) {
            const int r = im.rgba[k * 4], g = im.rgba[k * 4 + 1], b = im.rgba[k * 4 + 2];
            blue += b >= r + 12 && r + g + b < 3 * 125;
        }
        return double(blue) / double(std::size_t(im.width) * im.height);
    };
    const double sea = blue_share(coast), land = blue_share(raised);
    EXPECT_GT(sea, 0.25) << "the sea does not read as water";
    EXPECT_LT(land, 0.01) << "land drawn as water";
    fs::remove_all(dir);
}

TEST(TerrainPoints, PlyCsvAndXyzOfTheSamePointsRenderAlike)
{
    // The same scattered points (a hill sampled on a jittered grid) as binary PLY, CSV with its
    // columns in another order, and x y z text: triangulated and resampled alike, so the three
    // frames are the same bytes.
    const fs::path dir = kiri::test::temp_path("terrain_points");
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::string ply_body, csv = "z,x,y\n", xyz;
    int n = 0;
    for (int j = 0; j < 40; ++j)
        for (int i = 0; i < 40; ++i, ++n) {
            const double x = 25.0 * i + 7.0 * std::sin(3.1 * i + j), y = 25.0 * j + 7.0 * std::cos(1.7 * j + i);
            const double z = 200.0 + 300.0 * gauss(x / 1000.0, y / 1000.0, 0.5, 0.5, 0.2);
            const std::string sx = std::to_string(x), sy = std::to_string(y), sz = std::to_string(z);
            csv += sz + "," + sx + "," + sy + "\n";
            xyz += sx + " " + sy + " " + sz + "\n";
        }
    // The text files carry 6 decimals: the PLY gets the same rounded values.
    std::istringstream rounded(xyz);
    for (double v; rounded >> v;)
        ply_body.append(reinterpret_cast<const char*>(&v), sizeof v);
    std::ofstream(dir / "pts.ply", std::ios::binary)
        << "ply\nformat binary_little_endian 1.0\nelement vertex " << n
        << "\nproperty double x\nproperty double y\nproperty double z\nend_header\n"
        << ply_body;
    std::ofstream(dir / "pts.csv") << csv;
    std::ofstream(dir / "pts.xyz") << xyz;
    std::vector<std::string> frames;
    for (const char* name : {"pts.ply", "pts.csv", "pts.xyz"}) {
        const fs::path out = dir / (std::string(name) + ".png");
        const auto r = run_kiri("render " + (dir / name).string() + " -o " + out.string() +
                                " --width 96 --height 54 --mode terrain");
        ASSERT_EQ(r.exit_code, 0) << name << ": " << r.err;
        EXPECT_NE(r.err.find("/terrain/cell_size 25"), std::string::npos) << r.err;
        frames.push_back(read_all(out));
    }
    EXPECT_EQ(frames[0], frames[2]) << "PLY and xyz differ";
    EXPECT_EQ(frames[1], frames[2]) << "CSV and xyz differ";
    fs::remove_all(dir);
}

TEST(TerrainStarter, KiriNewSpellsOutTheSceneItRenders)
{
    const fs::path dir = kiri::test::temp_path("terrain_starter");
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path dem = write_geotiff(corpus()[1], dir), scene = dir / "scene.json";
    const auto made = run_kiri("new " + dem.string() + " -o " + scene.string());
    ASSERT_EQ(made.exit_code, 0) << made.err;
    const std::string text = read_all(scene);
    for (const char* key : {"\"exaggeration\"", "\"patch_size\"", "\"top\"", "\"cameras\"", "\"overview\"",
                            "\"valley\"", "\"inside\"", "\"direction\""})
        EXPECT_NE(text.find(key), std::string::npos) << key;
    EXPECT_NE(text.find("\"path\": \"peak.tif\""), std::string::npos) << "relative to the scene's folder";
    // The starter renders what the bare DEM renders: every derived value is in it.
    const fs::path a = dir / "dem.png", b = dir / "scene.png";
    ASSERT_EQ(
        run_kiri("render " + dem.string() + " -o " + a.string() + " --width 96 --height 54 --mode layers").exit_code,
        0);
    const auto r = run_kiri("render " + scene.string() + " -o " + b.string() + " --width 96 --height 54 --mode layers");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err.find("kiri: derived"), std::string::npos) << "nothing left to derive: " << r.err;
    EXPECT_EQ(read_all(a), read_all(b));
    // An existing file is kept unless --force.
    const auto again = run_kiri("new " + dem.string() + " -o " + scene.string());
    EXPECT_EQ(again.exit_code, 2);
    EXPECT_EQ(again.error_lines(), 1) << again.err;
    EXPECT_EQ(run_kiri("new " + dem.string() + " -o " + scene.string() + " --force").exit_code, 0);
    fs::remove_all(dir);
}
