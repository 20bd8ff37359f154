#pragma once
// The fixture of the bad-input tests: a private folder per test, generators of broken files,
// and the contract every case must meet (exit 2, one line naming the file and the field, no
// output or temporary file left behind).
#include <gtest/gtest.h>

#include <gdal.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli/kiri_runner.hpp"
#include "temp_path.hpp"

namespace kiri::test {

namespace fs = std::filesystem;

class BadInput : public ::testing::Test {
protected:
    void SetUp() override
    {
        dir_ = kiri::test::temp_path("bad_input_" +
                                     std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        GDALAllRegister();
    }
    void TearDown() override { fs::remove_all(dir_); }

    fs::path file(const std::string& name, const std::string& content) const
    {
        const fs::path p = dir_ / name;
        std::ofstream(p, std::ios::binary) << content;
        return p;
    }
    // A scene that renders the given raster (so every raster problem is also checked through
    // `kiri render`, the command users run most).
    fs::path scene_for(const fs::path& raster) const
    {
        return file("scene.json", R"({"terrain": {"path": ")" + raster.string() + R"("}})");
    }
    fs::path geotiff(const std::string& name, int w, int h, double value, bool with_nodata,
                     const std::vector<std::string>& options = {}) const
    {
        const fs::path p = dir_ / name;
        std::vector<const char*> opts;
        for (const std::string& o : options)
            opts.push_back(o.c_str());
        opts.push_back(nullptr);
        GDALDatasetH ds =
            GDALCreate(GDALGetDriverByName("GTiff"), p.c_str(), w, h, 1, GDT_Float32, const_cast<char**>(opts.data()));
        double gt[6] = {500000.0, 30.0, 0.0, 4000000.0, 0.0, -30.0};
        GDALSetGeoTransform(ds, gt);
        GDALRasterBandH band = GDALGetRasterBand(ds, 1);
        if (with_nodata)
            GDALSetRasterNoDataValue(band, value);
        if (std::size_t(w) * h < 1000000) {
            std::vector<float> data(std::size_t(w) * h, float(value));
            EXPECT_EQ(GDALRasterIO(band, GF_Write, 0, 0, w, h, data.data(), w, h, GDT_Float32, 0, 0), CE_None);
        }
        GDALClose(ds);
        return p;
    }

    // The contract of every bad-input case.
    void expect_refused(const RunResult& r, const std::vector<std::string>& mentions, const fs::path& output) const
    {
        EXPECT_EQ(r.exit_code, 2) << r.err;
        EXPECT_EQ(r.error_lines(), 1) << r.err;
        EXPECT_EQ(r.err.rfind("kiri: ", 0), 0u) << r.err;
        for (const std::string& m : mentions)
            EXPECT_NE(r.err.find(m), std::string::npos) << "stderr does not mention \"" << m << "\": " << r.err;
        EXPECT_FALSE(fs::exists(output)) << output;
        if (!fs::is_directory(output.parent_path()))
            return;
        for (const auto& entry : fs::directory_iterator(output.parent_path()))
            EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << "leftover " << entry.path();
    }
    RunResult render(const fs::path& scene) const
    {
        return run_kiri("render " + shell_quote(scene.string()) + " -o " + shell_quote(out().string()) +
                        " --width 64 --height 48");
    }
    fs::path out() const { return dir_ / "out.png"; }

    fs::path dir_;
};

}  // namespace kiri::test
