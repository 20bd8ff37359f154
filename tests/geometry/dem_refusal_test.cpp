// DEM loading's bad input: each raster refused with one line naming the file and the property,
// and nothing printed by GDAL (dem_fixture.hpp).
#include <gtest/gtest.h>

#include "dem_fixture.hpp"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/terrain/dem.hpp"

namespace fs = std::filesystem;
using namespace kiri::geometry;
using kiri::test::Dem;
using kiri::test::expect_refused;
using kiri::test::grid_values;

TEST_F(Dem, MissingFile)
{
    const fs::path path = dir / "nowhere.tif";
    expect_refused<kiri::InputError>([&] { load_dem(path); }, path, "file", "no such file");
    expect_refused<kiri::InputError>([&] { dem_info(path); }, path, "file", "no such file");
}

TEST_F(Dem, NotARaster)
{
    const auto path = write_text("notes.tif", "These are field notes, not a GeoTIFF.\n");
    expect_refused<kiri::InputError>([&] { load_dem(path); }, path, "format", "not a raster");
}

TEST_F(Dem, ZeroByteFile)
{
    const auto path = write_text("empty.tif", "");
    expect_refused<kiri::InputError>([&] { load_dem(path); }, path, "size", "0 bytes");
}

TEST_F(Dem, TruncatedTiff)
{
    const int w = 64, h = 64;
    const double gt[6] = {0.0, 1.0, 0.0, 64.0, 0.0, -1.0};
    const auto full =
        write("full.tif", "GTiff", w, h, GDT_Float32, grid_values(w, h, [](int c, int r) { return c * r; }), gt, 32616);
    ASSERT_EQ(load_dem(full).nx, w);  // whole, it loads
    std::ifstream in(full, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto cut = write_text("cut.tif", bytes.substr(0, bytes.size() / 2));
    // GDAL writes the directory first, so the file opens and the read fails.
    expect_refused<kiri::InputError>([&] { load_dem(cut); }, cut, "data", "truncated");
}

TEST_F(Dem, AllNodata)
{
    const double gt[6] = {0.0, 1.0, 0.0, 4.0, 0.0, -1.0};
    const double nd = -32768.0;
    const auto path = write("void.tif", "GTiff", 4, 4, GDT_Int16, std::vector<double>(16, nd), gt, 32616, &nd);
    expect_refused<kiri::InputError>([&] { load_dem(path); }, path, "nodata", "every cell");
}

TEST_F(Dem, AbsurdDimensionsAreRefusedBeforeAllocating)
{
    // 200000 x 200000 cells (40 G): sparse, so a few kB on disk; loading would need ~630 GiB.
    const double gt[6] = {0.0, 1.0, 0.0, 200000.0, 0.0, -1.0};
    const auto path = write("huge.tif", "GTiff", 200000, 200000, GDT_Byte, {}, gt, 32616, nullptr,
                            {"SPARSE_OK=TRUE", "TILED=YES", "BLOCKXSIZE=4096", "BLOCKYSIZE=4096"});
    ASSERT_LT(fs::file_size(path), 100000u);
    expect_refused<kiri::LimitError>([&] { load_dem(path); }, path, "size", "MiB");
    expect_refused<kiri::LimitError>([&] { dem_info(path); }, path, "size", "max_cells");
    // The limit is the option: a small raster above a small limit is refused too.
    const auto small = write("small.tif", "GTiff", 10, 10, GDT_Byte, std::vector<double>(100, 1.0), gt, 32616);
    DemOptions opt;
    opt.max_cells = 99;
    expect_refused<kiri::LimitError>([&] { load_dem(small, opt); }, small, "size", "100 cells");
    opt.max_cells = 100;
    EXPECT_EQ(load_dem(small, opt).size(), 100u);
}

TEST_F(Dem, ABlockLargerThanTheLimitIsRefusedBeforeDecoding)
{
    // 64 x 64 cells in one sparse 16384 x 16384 tile (a few kB on disk): GDAL would allocate and
    // fill the tile's 2 GiB to read the first cell (the DEM fuzzer's out-of-memory finding).
    const double gt[6] = {0.0, 1.0, 0.0, 64.0, 0.0, -1.0};
    const auto path = write("tile.tif", "GTiff", 64, 64, GDT_Float64, {}, gt, 32616, nullptr,
                            {"SPARSE_OK=TRUE", "TILED=YES", "BLOCKXSIZE=16384", "BLOCKYSIZE=16384"});
    ASSERT_LT(fs::file_size(path), 100000u);
    expect_refused<kiri::LimitError>([&] { load_dem(path); }, path, "block size", "2048 MiB");
    expect_refused<kiri::LimitError>([&] { dem_info(path); }, path, "block size", "max_cells");
    // The limit is the option's: 16 x 16 cells in 32 x 32 tiles load up to a block of it.
    const auto small = write("small_tiles.tif", "GTiff", 16, 16, GDT_Byte, std::vector<double>(256, 1.0), gt, 32616,
                             nullptr, {"TILED=YES", "BLOCKXSIZE=32", "BLOCKYSIZE=32"});
    DemOptions opt;
    opt.max_cells = 1023;
    expect_refused<kiri::LimitError>([&] { load_dem(small, opt); }, small, "block size", "32 x 32 cells");
    opt.max_cells = 1024;
    EXPECT_EQ(load_dem(small, opt).size(), 256u);
}

TEST_F(Dem, RotatedGeotransformIsRefused)
{
    const double gt[6] = {0.0, 1.0, 0.2, 4.0, 0.1, -1.0};
    const auto path = write("rotated.tif", "GTiff", 4, 4, GDT_Byte, std::vector<double>(16, 1.0), gt, 32616);
    expect_refused<kiri::InputError>([&] { load_dem(path); }, path, "geotransform", "rotated");
}

TEST_F(Dem, TruncatedCompressedJacksboro)
{
    // The real, deflate-compressed file cut at 60 %: the directory survives, the strips do not.
    std::ifstream in(fs::path(KIRI_DATA_DIR) / "terrains" / "jacksboro_fault_dem.tif", std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto cut = write_text("jacksboro_cut.tif", bytes.substr(0, bytes.size() * 6 / 10));
    expect_refused<kiri::InputError>([&] { load_dem(cut); }, cut, "data", "GDAL:");
}

TEST_F(Dem, CorruptCompressedStrips)
{
    // Deflate strips overwritten with garbage in the middle of the file.
    const int w = 64, h = 64;
    const double gt[6] = {0.0, 1.0, 0.0, 64.0, 0.0, -1.0};
    const auto path = write("deflate.tif", "GTiff", w, h, GDT_Float32,
                            grid_values(w, h, [](int c, int r) { return std::sin(c * 0.3) * r; }), gt, 32616, nullptr,
                            {"COMPRESS=DEFLATE", "BLOCKYSIZE=8"});
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(std::streamoff(fs::file_size(path) / 2));
    const std::string junk(2000, '\x5a');
    f.write(junk.data(), std::streamsize(junk.size()));
    f.close();
    expect_refused<kiri::InputError>([&] { load_dem(path); }, path, "data", "corrupt");
}

TEST_F(Dem, ZeroSizeGridHeader)
{
    // An ASCII grid whose header declares no columns.
    const auto path = write_text("zero.asc", "ncols 0\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 1\n");
    expect_refused<kiri::InputError>([&] { load_dem(path); }, path, "format", "not a raster");
}
