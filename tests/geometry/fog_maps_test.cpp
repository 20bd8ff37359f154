// Fog maps: GeoTIFFs carry the DEM's georeferencing and row order, masks round-trip,
// the same input writes the same bytes.
#include <gtest/gtest.h>

#include <gdal.h>
#include <ogr_srs_api.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "kiri/geometry/terrain/dem.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/placement/fog_maps.hpp"
#include "kiri/geometry/placement/fog_placement.hpp"
#include "temp_path.hpp"

using namespace kiri::geometry;
namespace fs = std::filesystem;

namespace {

const fs::path jacksboro = fs::path(KIRI_DATA_DIR) / "terrains/jacksboro_fault_dem.tif";

std::string bytes(const fs::path& p)
{
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace

TEST(FogMaps, GeoTiffKeepsTheDemsGeoreferencingAndRows)
{
    const Heightfield hf = load_dem(jacksboro);
    const fs::path out = kiri::test::temp_path("fog_map.tif");
    std::vector<std::uint8_t> defined(hf.size(), 1);
    defined[0] = 0;  // south-west corner: nodata
    write_geotiff_map(out, hf, hf.z, defined, 0.5, "half the ground", {{"KIRI_TEST", "42"}});
    GDALAllRegister();
    GDALDatasetH ds = GDALOpen(out.c_str(), GA_ReadOnly);
    ASSERT_NE(ds, nullptr);
    GDALDatasetH dem = GDALOpen(jacksboro.c_str(), GA_ReadOnly);
    double a[6], b[6];
    GDALGetGeoTransform(ds, a);
    GDALGetGeoTransform(dem, b);
    for (int k = 0; k < 6; ++k)
        EXPECT_DOUBLE_EQ(a[k], b[k]);
    OGRSpatialReferenceH sa = GDALGetSpatialRef(ds), sb = GDALGetSpatialRef(dem);
    ASSERT_NE(sa, nullptr);
    EXPECT_TRUE(OSRIsSame(sa, sb));
    EXPECT_STREQ(GDALGetMetadataItem(ds, "KIRI_TEST", nullptr), "42");
    // Pixel (col, row) of the map is half the DEM's pixel (col, row): same row order.
    GDALRasterBandH mb = GDALGetRasterBand(ds, 1), db = GDALGetRasterBand(dem, 1);
    int has = 0;
    EXPECT_EQ(GDALGetRasterNoDataValue(mb, &has), kMapNodata);
    EXPECT_TRUE(has);
    for (auto [col, row] : {std::pair{0, 0}, {17, 200}, {402, 343}, {0, 343}}) {
        float m = 0, d = 0;
        ASSERT_EQ(GDALRasterIO(mb, GF_Read, col, row, 1, 1, &m, 1, 1, GDT_Float32, 0, 0), CE_None);
        ASSERT_EQ(GDALRasterIO(db, GF_Read, col, row, 1, 1, &d, 1, 1, GDT_Float32, 0, 0), CE_None);
        if (col == 0 && row == 343)
            EXPECT_EQ(m, float(kMapNodata));  // local (0, 0) is the south-west corner
        else
            EXPECT_FLOAT_EQ(m, 0.5f * d);
    }
    GDALClose(ds);
    GDALClose(dem);
    // Same input, same bytes.
    const fs::path again = kiri::test::temp_path("fog_map_again.tif");
    write_geotiff_map(again, hf, hf.z, defined, 0.5, "half the ground", {{"KIRI_TEST", "42"}});
    EXPECT_EQ(bytes(out), bytes(again));
    fs::remove(out);
    fs::remove(again);
}

TEST(FogMaps, MaskPngRoundTripsAndWrongSizesAreRefused)
{
    const Heightfield hf = load_dem(jacksboro);
    std::vector<std::uint8_t> mask(hf.size(), 0);
    for (int j = 0; j < hf.ny; ++j)
        for (int i = 0; i < hf.nx; ++i)
            mask[std::size_t(j) * hf.nx + i] = (i < 50 && j < 30) || (i == 400 && j == 340);
    const fs::path png = kiri::test::temp_path("mask.png");
    write_mask_png(png, hf, mask);
    EXPECT_EQ(read_mask(png, hf, "s.json", "/fog/fill/seeds/mask"), mask);
    EXPECT_FALSE(fs::exists(png.string() + ".aux.xml"));
    Heightfield smaller = hf;
    smaller.nx = 10;
    smaller.ny = 10;
    smaller.z.resize(100);
    try {
        read_mask(png, smaller, "s.json", "/fog/fill/seeds/mask");
        FAIL();
    } catch (const kiri::InputError& e) {
        EXPECT_EQ(e.field(), "/fog/fill/seeds/mask");
        EXPECT_NE(std::string(e.what()).find("403 x 344 pixels"), std::string::npos);
    }
    EXPECT_THROW(read_mask(png.string() + ".missing", hf, "s.json", "f"), kiri::InputError);
    fs::remove(png);
}

TEST(FogMaps, TheTerrainsLatitude)
{
    const Heightfield hf = load_dem(jacksboro);
    EXPECT_NEAR(terrain_latitude(hf, 0.0), 36.5896, 1e-3);
    Heightfield local = hf;
    local.georef = {};
    EXPECT_EQ(terrain_latitude(local, 45.0), 45.0);
}
