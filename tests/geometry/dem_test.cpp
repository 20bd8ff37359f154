// DEM loading: the bundled Jacksboro GeoTIFF and small rasters of each format written here (by
// GDAL or by hand) with known values (the bad rasters kiri refuses: dem_refusal_test.cpp).
#include <gtest/gtest.h>

#include "dem_fixture.hpp"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include "kiri/geometry/terrain/dem.hpp"
#include "kiri/geometry/core/error.hpp"

namespace fs = std::filesystem;
using namespace kiri::geometry;
using kiri::test::Dem;
using kiri::test::expect_refused;
using kiri::test::grid_values;

namespace {

// Metres per degree from the classic series in cos(k phi) (an independent oracle for the
// loader's ellipsoid radii; the series are good to ~1 cm).
double series_m_per_deg_lat(double phi_deg)
{
    const double p = phi_deg * M_PI / 180.0;
    return 111132.92 - 559.82 * std::cos(2 * p) + 1.175 * std::cos(4 * p) - 0.0023 * std::cos(6 * p);
}
double series_m_per_deg_lon(double phi_deg)
{
    const double p = phi_deg * M_PI / 180.0;
    return 111412.84 * std::cos(p) - 93.5 * std::cos(3 * p) + 0.118 * std::cos(5 * p);
}

}  // namespace

TEST_F(Dem, JacksboroLoadsInLocalMetres)
{
    const fs::path path = fs::path(KIRI_DATA_DIR) / "terrains" / "jacksboro_fault_dem.tif";
    const Heightfield hf = load_dem(path);
    EXPECT_EQ(hf.nx, 403);
    EXPECT_EQ(hf.ny, 344);
    const auto [lo, hi] = std::minmax_element(hf.z.begin(), hf.z.end());
    EXPECT_EQ(*lo, 236.0);
    EXPECT_EQ(*hi, 1076.0);
    EXPECT_TRUE(std::all_of(hf.valid.begin(), hf.valid.end(), [](auto v) { return v == 1; }));
    // 3 arc-second cells at the centre latitude.
    const double lat = 36.7329166666667 - 172 * 3.0 / 3600.0;
    EXPECT_NEAR(hf.dx, 3.0 / 3600.0 * series_m_per_deg_lon(lat), 0.01);
    EXPECT_NEAR(hf.dy, 3.0 / 3600.0 * series_m_per_deg_lat(lat), 0.01);
    EXPECT_NEAR(hf.dx, 74.0, 1.0);
    EXPECT_NEAR(hf.dy, 93.0, 1.0);
    // Origin at the centre; j = 0 is the south edge.
    EXPECT_NEAR(hf.x0 + hf.x_max(), 0.0, 1e-9);
    EXPECT_NEAR(hf.y0 + hf.y_max(), 0.0, 1e-9);
    EXPECT_TRUE(hf.georef.geographic);
    EXPECT_NEAR(hf.georef.origin_x, -84.41375 + 201.5 * 3.0 / 3600.0, 1e-9);
    EXPECT_NEAR(hf.georef.origin_y, lat, 1e-9);
    EXPECT_NE(hf.georef.crs_wkt.find("WGS"), std::string::npos);
    EXPECT_EQ(hf.georef.source_width, 403);

    // Row order against GDAL's own read of the file: source row 343 is j = 0.
    GDALAllRegister();
    GDALDataset* ds = GDALDataset::Open(path.string().c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY);
    ASSERT_NE(ds, nullptr);
    std::vector<double> row(403);
    ASSERT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Read, 0, 343, 403, 1, row.data(), 403, 1, GDT_Float64, 0, 0, nullptr),
              CE_None);
    GDALClose(ds);
    for (int i = 0; i < 403; ++i)
        ASSERT_EQ(hf.at(i, 0), row[i]);

    const DemInfo info = dem_info(path);
    EXPECT_EQ(info.driver, "GTiff");
    EXPECT_EQ(info.width, 403);
    EXPECT_EQ(info.height, 344);
    EXPECT_EQ(info.z_min, 236.0);
    EXPECT_EQ(info.z_max, 1076.0);
    EXPECT_EQ(info.nodata_count, 0u);
    EXPECT_DOUBLE_EQ(info.cell_dx_m, hf.dx);
    EXPECT_DOUBLE_EQ(info.extent_y_m, 344 * hf.dy);
    EXPECT_TRUE(info.geographic);
    EXPECT_EQ(info.crs_name, "WGS 84");
}

TEST_F(Dem, ProjectedNorthUpGeoTiff)
{
    const int w = 7, h = 5;
    const double gt[6] = {500000.0, 10.0, 0.0, 4000000.0, 0.0, -10.0};
    const auto path = write("utm.tif", "GTiff", w, h, GDT_Int16,
                            grid_values(w, h, [](int c, int r) { return c + 100.0 * r; }), gt, 32616);
    const Heightfield hf = load_dem(path);
    ASSERT_EQ(hf.nx, w);
    ASSERT_EQ(hf.ny, h);
    EXPECT_DOUBLE_EQ(hf.dx, 10.0);
    EXPECT_DOUBLE_EQ(hf.dy, 10.0);
    EXPECT_DOUBLE_EQ(hf.x0, -30.0);
    EXPECT_DOUBLE_EQ(hf.y0, -20.0);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i)
            EXPECT_EQ(hf.at(i, j), i + 100.0 * (h - 1 - j));
    EXPECT_FALSE(hf.georef.geographic);
    EXPECT_DOUBLE_EQ(hf.georef.origin_x, 500035.0);
    EXPECT_DOUBLE_EQ(hf.georef.origin_y, 3999975.0);
}

TEST_F(Dem, SouthUpNonSquareCells)
{
    const int w = 6, h = 4;
    const double gt[6] = {500000.0, 10.0, 0.0, 4000000.0, 0.0, 25.0};  // row 0 is the south edge
    const auto path = write("southup.tif", "GTiff", w, h, GDT_Float32,
                            grid_values(w, h, [](int c, int r) { return c + 100.0 * r; }), gt, 32616);
    const Heightfield hf = load_dem(path);
    EXPECT_DOUBLE_EQ(hf.dx, 10.0);
    EXPECT_DOUBLE_EQ(hf.dy, 25.0);
    EXPECT_DOUBLE_EQ(hf.y0, -37.5);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i)
            EXPECT_EQ(hf.at(i, j), i + 100.0 * j);
    EXPECT_DOUBLE_EQ(hf.georef.origin_y, 4000050.0);
}

TEST_F(Dem, ProjectedFeetUseTheCrsLinearUnit)
{
    const double gt[6] = {1800000.0, 10.0, 0.0, 600000.0, 0.0, -10.0};  // NAD83 / Tennessee (ftUS)
    const auto path = write("ftus.tif", "GTiff", 3, 3, GDT_Float32, std::vector<double>(9, 5.0), gt, 2274);
    const Heightfield hf = load_dem(path);
    EXPECT_NEAR(hf.dx, 10.0 * 1200.0 / 3937.0, 1e-9);
    EXPECT_NEAR(hf.dy, 10.0 * 1200.0 / 3937.0, 1e-9);
}

TEST_F(Dem, EsriAsciiGridWithANodataCell)
{
    // Written by hand: rows run north to south; z = 2 i + 3 j in local (south-up) indices.
    const auto path = write_text("grid.asc",
                                 "ncols 4\nnrows 3\nxllcorner 1000\nyllcorner 2000\ncellsize 30\n"
                                 "NODATA_value -9999\n"
                                 "6 8 10 12\n"
                                 "3 -9999 7 9\n"
                                 "0 2 4 6\n");
    const Heightfield hf = load_dem(path);
    ASSERT_EQ(hf.nx, 4);
    ASSERT_EQ(hf.ny, 3);
    EXPECT_DOUBLE_EQ(hf.dx, 30.0);
    EXPECT_DOUBLE_EQ(hf.dy, 30.0);
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 4; ++i) {
            EXPECT_DOUBLE_EQ(hf.at(i, j), 2.0 * i + 3.0 * j);  // the hole refilled exactly
            EXPECT_EQ(hf.valid[j * 4 + i], (i == 1 && j == 1) ? 0 : 1);
        }
    EXPECT_DOUBLE_EQ(hf.georef.origin_x, 1060.0);
    EXPECT_DOUBLE_EQ(hf.georef.origin_y, 2045.0);
    const DemInfo info = dem_info(path);
    EXPECT_EQ(info.driver, "AAIGrid");
    EXPECT_EQ(info.nodata_count, 1u);
    EXPECT_EQ(info.z_min, 0.0);
    EXPECT_EQ(info.z_max, 12.0);
    EXPECT_DOUBLE_EQ(info.extent_x_m, 120.0);
}

TEST_F(Dem, SrtmHgtTileIsGeographic)
{
    // N36W085.hgt written by hand: 1201 x 1201 big-endian int16, rows from the north,
    // -32768 = void. Value: column + 2 * row (source indices).
    const int n = 1201;
    std::vector<unsigned char> bytes(std::size_t(n) * n * 2);
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) {
            const std::int16_t v = (r == 600 && c == 600) ? std::int16_t(-32768) : std::int16_t(c + 2 * r);
            const auto u = static_cast<std::uint16_t>(v);
            bytes[(std::size_t(r) * n + c) * 2] = static_cast<unsigned char>(u >> 8);
            bytes[(std::size_t(r) * n + c) * 2 + 1] = static_cast<unsigned char>(u & 0xff);
        }
    const fs::path path = dir / "N36W085.hgt";
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));

    const Heightfield hf = load_dem(path);
    ASSERT_EQ(hf.nx, n);
    ASSERT_EQ(hf.ny, n);
    EXPECT_TRUE(hf.georef.geographic);
    EXPECT_NEAR(hf.georef.origin_x, -84.5, 1e-9);
    EXPECT_NEAR(hf.georef.origin_y, 36.5, 1e-9);
    EXPECT_NEAR(hf.dx, 3.0 / 3600.0 * series_m_per_deg_lon(36.5), 0.01);
    EXPECT_NEAR(hf.dy, 3.0 / 3600.0 * series_m_per_deg_lat(36.5), 0.01);
    EXPECT_EQ(hf.at(0, 0), 2.0 * (n - 1));          // south-west corner: source row 1200
    EXPECT_EQ(hf.at(n - 1, n - 1), double(n - 1));  // north-east corner: source row 0
    // The void at the centre: masked, and refilled exactly (z is linear in i and j).
    EXPECT_EQ(hf.valid[std::size_t(600) * n + 600], 0);
    EXPECT_DOUBLE_EQ(hf.at(600, 600), 600.0 + 2.0 * 600.0);
}

TEST_F(Dem, PngHeightmaps8And16Bit)
{
    const int w = 5, h = 4;
    DemOptions opt;
    opt.cell_size = 2.0;
    opt.vertical_scale = 0.5;
    opt.vertical_offset = 100.0;
    const auto p8 = write("h8.png", "PNG", w, h, GDT_Byte, grid_values(w, h, [](int c, int r) { return 10.0 * c + r; }),
                          nullptr, 0);
    const auto p16 = write("h16.png", "PNG", w, h, GDT_UInt16,
                           grid_values(w, h, [](int c, int r) { return 65535.0 - 1000.0 * c - r; }), nullptr, 0);
    const Heightfield a = load_dem(p8, opt), b = load_dem(p16, opt);
    ASSERT_EQ(a.nx, w);
    ASSERT_EQ(a.ny, h);
    EXPECT_DOUBLE_EQ(a.dx, 2.0);
    EXPECT_DOUBLE_EQ(a.dy, 2.0);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            const int row = h - 1 - j;  // image row 0 is the north edge
            EXPECT_DOUBLE_EQ(a.at(i, j), 100.0 + 0.5 * (10.0 * i + row));
            EXPECT_DOUBLE_EQ(b.at(i, j), 100.0 + 0.5 * (65535.0 - 1000.0 * i - row));
        }
    // Without a cell size the PNG is refused, naming the option.
    expect_refused<kiri::InputError>([&] { load_dem(p8); }, p8, "cell_size", "cell size");
}

TEST_F(Dem, NodataAndNanCellsAreMaskedAndFilled)
{
    // Plane z = 5 + i - 2 j (local indices) on a 12 x 10 grid, with a lone NaN, a lone nodata
    // cell and a 3 x 3 nodata block.
    const int w = 12, h = 10;
    const double gt[6] = {0.0, 1.0, 0.0, 10.0, 0.0, -1.0};
    const double nd = -9999.0;
    const auto plane = [&](int i, int j) { return 5.0 + i - 2.0 * j; };
    const auto hole = [](int i, int j) {
        return (i == 2 && j == 2) || (i == 9 && j == 7) || (i >= 6 && i <= 8 && j >= 2 && j <= 4);
    };
    const auto values = grid_values(w, h, [&](int c, int r) {
        const int j = h - 1 - r;
        if (c == 2 && j == 2)
            return double(NAN);
        return hole(c, j) ? nd : plane(c, j);
    });
    const auto path = write("holes.tif", "GTiff", w, h, GDT_Float32, values, gt, 32616, &nd);
    const Heightfield hf = load_dem(path);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            EXPECT_EQ(hf.valid[j * w + i], hole(i, j) ? 0 : 1) << i << "," << j;
            EXPECT_TRUE(std::isfinite(hf.at(i, j)));
            if (!hole(i, j) || (i == 2 && j == 2) || (i == 9 && j == 7)) {
                EXPECT_DOUBLE_EQ(hf.at(i, j), plane(i, j)) << i << "," << j;
            }
        }
    // The block is filled by the membrane over the valid cells, which refills a plane exactly.
    for (int j = 2; j <= 4; ++j)
        for (int i = 6; i <= 8; ++i)
            EXPECT_NEAR(hf.at(i, j), plane(i, j), 1e-8) << i << "," << j;
    EXPECT_EQ(dem_info(path).nodata_count, 11u);
    EXPECT_TRUE(hf.warnings.empty()) << hf.warnings.front();
}

TEST_F(Dem, VoidsAreFilledByAMembraneWithoutSpikes)
{
    // A cone whose apex lies in a 9 x 7 NaN hole, and a nodata border three cells wide on the
    // west: each filled cell is the mean of its 4-neighbours (a discrete harmonic function, so
    // no spike and no crease), and no filled value leaves the range of the valid cells around
    // it (maximum principle).
    const int w = 60, h = 50;
    const double gt[6] = {500000.0, 30.0, 0.0, 4000000.0, 0.0, -30.0};
    const double nd = -9999.0;
    const auto cone = [](int i, int j) {
        return 1000.0 + 800.0 * std::max(0.0, 1.0 - std::hypot(i - 30, j - 25) / 25.0);
    };
    const auto hole = [](int i, int j) { return i >= 26 && i <= 34 && j >= 22 && j <= 28; };
    const auto values = grid_values(w, h, [&](int c, int r) {
        const int j = h - 1 - r;
        if (c < 3)
            return nd;
        return hole(c, j) ? double(NAN) : cone(c, j);
    });
    const auto path = write("cone.tif", "GTiff", w, h, GDT_Float32, values, gt, 32633, &nd);
    const Heightfield hf = load_dem(path);
    double rim_lo = INFINITY, rim_hi = -INFINITY;
    for (int j = 21; j <= 29; ++j)
        for (int i = 25; i <= 35; ++i)
            if (!hole(i, j)) {
                rim_lo = std::min(rim_lo, hf.at(i, j));
                rim_hi = std::max(rim_hi, hf.at(i, j));
            }
    int filled = 0;
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            if (hf.valid[j * w + i])
                continue;
            ++filled;
            double sum = 0.0;
            int n = 0;
            for (const auto& [a, b] : {std::pair{i - 1, j}, {i + 1, j}, {i, j - 1}, {i, j + 1}})
                if (a >= 0 && a < w && b >= 0 && b < h)
                    sum += hf.at(a, b), ++n;
            EXPECT_NEAR(hf.at(i, j), sum / n, 1e-6) << i << "," << j;
            if (hole(i, j)) {
                EXPECT_GE(hf.at(i, j), rim_lo - 1e-9);
                EXPECT_LE(hf.at(i, j), rim_hi + 1e-9);
            }
        }
    EXPECT_EQ(filled, 9 * 7 + 3 * h);
    // The border is a continuation of the valid edge, not a wall: within the heights of the
    // first valid column's rows.
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < 3; ++i) {
            EXPECT_GE(hf.at(i, j), 1000.0 - 1e-9);
            EXPECT_LE(hf.at(i, j), cone(3, 25) + 1e-9);
        }
}

TEST_F(Dem, UndeclaredFillValuesAndImpossibleHeightsAreVoidsWithAWarning)
{
    // A float32 GeoTIFF with no nodata tag whose voids hold -3.4e38 (real exports), -32768 and
    // -9999, and one cell at 20 km: all voids, counted in two one-line warnings.
    const int w = 20, h = 16;
    const double gt[6] = {300000.0, 10.0, 0.0, 5000000.0, 0.0, -10.0};
    const auto values = grid_values(w, h, [&](int c, int r) {
        if (r == 3 && c < 5)
            return -3.4028234663852886e38;
        if (r == 8 && c == 8)
            return -32768.0;
        if (r == 9 && c == 9)
            return -9999.0;
        if (r == 12 && c == 2)
            return 20000.0;
        return 100.0 + c + r;
    });
    const auto path = write("fills.tif", "GTiff", w, h, GDT_Float32, values, gt, 32633);
    const Heightfield hf = load_dem(path);
    int voids = 0;
    for (std::size_t k = 0; k < hf.size(); ++k) {
        voids += hf.valid[k] ? 0 : 1;
        EXPECT_GE(hf.z[k], 100.0);
        EXPECT_LE(hf.z[k], 100.0 + w + h);
    }
    EXPECT_EQ(voids, 8);
    ASSERT_EQ(hf.warnings.size(), 2u);
    EXPECT_NE(hf.warnings[0].find("7 cells hold an undeclared fill value"), std::string::npos) << hf.warnings[0];
    EXPECT_NE(hf.warnings[1].find("1 cell lies outside -12 km..+9 km"), std::string::npos) << hf.warnings[1];
    for (const std::string& warning : hf.warnings) {
        EXPECT_EQ(warning.find('\n'), std::string::npos);
        EXPECT_EQ(warning.rfind(path.string() + ": nodata: ", 0), 0u) << warning;
    }
    EXPECT_EQ(dem_info(path).nodata_count, 8u);
    EXPECT_EQ(dem_info(path).warnings, hf.warnings);
}

TEST_F(Dem, HeightsMostlyOffTheEarthAreRefusedNamingTheVerticalScale)
{
    // Centimetres written as if they were metres: 150 km mountains.
    const double gt[6] = {300000.0, 10.0, 0.0, 5000000.0, 0.0, -10.0};
    const auto path = write("cm.tif", "GTiff", 8, 8, GDT_Float32,
                            grid_values(8, 8, [](int c, int r) { return 150000.0 + c * r; }), gt, 32633);
    expect_refused<kiri::InputError>([&] { load_dem(path); }, path, "vertical_scale", "-12 km..+9 km");
}

TEST_F(Dem, VerticalFeetAreConvertedToMetres)
{
    const double gt[6] = {300000.0, 10.0, 0.0, 5000000.0, 0.0, -10.0};
    const auto path = write("feet.tif", "GTiff", 4, 4, GDT_Float32, std::vector<double>(16, 1000.0), gt, 32633);
    {
        GDALDataset* ds = GDALDataset::Open(path.string().c_str(), GDAL_OF_RASTER | GDAL_OF_UPDATE);
        ASSERT_NE(ds, nullptr);
        ds->GetRasterBand(1)->SetUnitType("ft");
        GDALClose(ds);
    }
    const Heightfield hf = load_dem(path);
    for (double z : hf.z)
        EXPECT_DOUBLE_EQ(z, 304.8);
}

TEST_F(Dem, DegreesWithoutACrsAreReadAsGeographicWithAWarning)
{
    // An ESRI ASCII grid at 30 arc-seconds with no .prj: its coordinates can only be degrees.
    const double cell = 1.0 / 120.0;
    std::string text = "ncols 6\nnrows 5\nxllcorner -84.5\nyllcorner 36.5\ncellsize " + std::to_string(cell) + "\n";
    for (int r = 0; r < 5; ++r) {
        for (int c = 0; c < 6; ++c)
            text += std::to_string(300 + 10 * c + r) + " ";
        text += "\n";
    }
    const auto path = write_text("degrees.asc", text);
    const Heightfield hf = load_dem(path);
    EXPECT_TRUE(hf.georef.geographic);
    const double lat = 36.5 + 2.5 * cell;
    EXPECT_NEAR(hf.dx, cell * series_m_per_deg_lon(lat), 0.01 * cell * 1000.0);
    EXPECT_NEAR(hf.dy, cell * series_m_per_deg_lat(lat), 0.01 * cell * 1000.0);
    ASSERT_EQ(hf.warnings.size(), 1u);
    EXPECT_NE(hf.warnings[0].find("plainly degrees"), std::string::npos) << hf.warnings[0];
    // A metric grid with the same values and 30 m cells stays metres, silently.
    std::string metric = text;
    metric.replace(metric.find("cellsize"), metric.find("\n", metric.find("cellsize")) - metric.find("cellsize"),
                   "cellsize 30");
    const Heightfield m = load_dem(write_text("metres.asc", metric));
    EXPECT_FALSE(m.georef.geographic);
    EXPECT_DOUBLE_EQ(m.dx, 30.0);
    EXPECT_TRUE(m.warnings.empty());
}

TEST_F(Dem, ResampleKeepsTheExtentAndReproducesAPlane)
{
    Heightfield src;
    src.nx = 9, src.ny = 7, src.dx = 3.0, src.dy = 5.0, src.x0 = -12.0, src.y0 = -15.0;
    for (int j = 0; j < src.ny; ++j)
        for (int i = 0; i < src.nx; ++i)
            src.z.push_back(1.0 + 0.25 * src.x_of(i) - 0.5 * src.y_of(j));
    src.valid.assign(src.z.size(), 1);
    const Heightfield r = resample(src, 33, 4);
    EXPECT_EQ(r.nx, 33);
    EXPECT_EQ(r.ny, 4);
    EXPECT_DOUBLE_EQ(r.x0, src.x0);
    EXPECT_NEAR(r.x_max(), src.x_max(), 1e-12);
    EXPECT_NEAR(r.y_max(), src.y_max(), 1e-12);
    for (int j = 0; j < r.ny; ++j)
        for (int i = 0; i < r.nx; ++i)
            EXPECT_NEAR(r.at(i, j), 1.0 + 0.25 * r.x_of(i) - 0.5 * r.y_of(j), 1e-12);
    EXPECT_THROW(resample(src, 1, 10), kiri::InputError);
    EXPECT_THROW(resample(src, 100000, 100000), kiri::LimitError);
}
