#pragma once
// The DEM tests' fixture (dem_test.cpp: loading; dem_refusal_test.cpp: bad rasters refused): a
// temporary folder per test, rasters written by GDAL or by hand, and the check that a refusal
// names the file and the field in one line.
#include <gtest/gtest.h>

#include "temp_path.hpp"

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <gdal_priv.h>
#include <ogr_spatialref.h>

namespace kiri::test {

namespace fs = std::filesystem;

class Dem : public ::testing::Test {
protected:
    fs::path dir;
    void SetUp() override
    {
        GDALAllRegister();
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = kiri::test::temp_path("dem_test_" + std::string(info->name()));
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }

    // Writes a one-band raster; values in source order (row 0 first). epsg 0: no CRS.
    fs::path write(const std::string& name, const char* driver, int w, int h, GDALDataType type,
                   const std::vector<double>& values, const double* gt, int epsg, const double* nodata = nullptr,
                   std::vector<std::string> options = {})
    {
        const fs::path path = dir / name;
        std::vector<char*> opts;
        for (auto& o : options)
            opts.push_back(o.data());
        opts.push_back(nullptr);
        if (values.empty()) {
            // No values: created in place (a MEM copy of a huge raster would be allocated).
            GDALDataset* out = GetGDALDriverManager()->GetDriverByName(driver)->Create(path.string().c_str(), w, h, 1,
                                                                                       type, opts.data());
            EXPECT_NE(out, nullptr) << "GDAL could not write " << path;
            if (gt)
                out->SetGeoTransform(const_cast<double*>(gt));
            GDALClose(out);
            return path;
        }
        GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
        GDALDataset* ds = mem->Create("", w, h, 1, type, nullptr);
        if (gt)
            ds->SetGeoTransform(const_cast<double*>(gt));
        if (epsg) {
            OGRSpatialReference srs;
            srs.importFromEPSG(epsg);
            srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
            ds->SetSpatialRef(&srs);
        }
        GDALRasterBand* band = ds->GetRasterBand(1);
        if (nodata)
            band->SetNoDataValue(*nodata);
        EXPECT_EQ(
            band->RasterIO(GF_Write, 0, 0, w, h, const_cast<double*>(values.data()), w, h, GDT_Float64, 0, 0, nullptr),
            CE_None);
        GDALDataset* out = GetGDALDriverManager()->GetDriverByName(driver)->CreateCopy(path.string().c_str(), ds, FALSE,
                                                                                       opts.data(), nullptr, nullptr);
        EXPECT_NE(out, nullptr) << "GDAL could not write " << path;
        GDALClose(out);
        GDALClose(ds);
        return path;
    }

    fs::path write_text(const std::string& name, const std::string& text)
    {
        const fs::path path = dir / name;
        std::ofstream(path, std::ios::binary) << text;
        return path;
    }
};

inline std::vector<double> grid_values(int w, int h, const std::function<double(int, int)>& f)
{
    std::vector<double> v;
    for (int row = 0; row < h; ++row)
        for (int col = 0; col < w; ++col)
            v.push_back(f(col, row));
    return v;
}

// Runs fn, expects an exception of type E whose what() names the file and whose field is
// the given one, and that GDAL printed nothing on stderr.
template <class E>
void expect_refused(const std::function<void()>& fn, const fs::path& file, const std::string& field,
                    const std::string& reason_part = "")
{
    ::testing::internal::CaptureStderr();
    try {
        fn();
        ::testing::internal::GetCapturedStderr();
        ADD_FAILURE() << "no exception for " << file;
    } catch (const E& e) {
        const std::string printed = ::testing::internal::GetCapturedStderr();
        EXPECT_EQ(printed, "") << "GDAL printed on stderr";
        EXPECT_EQ(e.file(), file.string());
        EXPECT_EQ(e.field(), field) << e.what();
        EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(reason_part), std::string::npos) << e.what();
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line: " << e.what();
    }
}

}  // namespace kiri::test
