// Linear radiance as OpenEXR (exr_image.hpp): values come back exactly (32-bit floats), rows in
// order; failures are one error naming the file, and no partial file is left.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "kiri/geometry/core/error.hpp"
#include "kiri/render/exr_image.hpp"
#include "temp_path.hpp"

namespace fs = std::filesystem;
using kiri::render::RadianceImage;

TEST(Exr, RoundTripsFloatsExactly)
{
    RadianceImage image{5, 3, {}};
    for (int k = 0; k < 5 * 3 * 4; ++k)  // distinct values, HDR and tiny ones, per channel and row
        image.rgba.push_back(float(std::ldexp(1.0 + 0.37 * k, k % 9 - 4)) * (k % 4 == 3 ? 0.5f : 1.0f));
    image.rgba[4] = 65504.0f * 4.0f;  // beyond half precision
    image.rgba[9] = 1e-7f;
    const fs::path path = kiri::test::temp_path("exr_test.exr");
    kiri::render::write_exr_atomic(path, image);
    const RadianceImage back = kiri::render::read_exr(path);
    EXPECT_EQ(back.width, 5);
    EXPECT_EQ(back.height, 3);
    EXPECT_EQ(back.rgba, image.rgba);
    for (const auto& entry : fs::directory_iterator(path.parent_path()))  // no temporary left
        EXPECT_EQ(entry.path().string().find("exr_test.exr.tmp"), std::string::npos) << entry.path();
    fs::remove(path);
}

TEST(Exr, ExtensionPicksTheFormat)
{
    EXPECT_TRUE(kiri::render::is_exr_path("a/b/frame.exr"));
    EXPECT_TRUE(kiri::render::is_exr_path("FRAME.EXR"));
    EXPECT_FALSE(kiri::render::is_exr_path("frame.png"));
    EXPECT_FALSE(kiri::render::is_exr_path("exr"));
}

TEST(Exr, UnwritablePathThrowsNamingTheFile)
{
    const RadianceImage image{1, 1, {1.0f, 2.0f, 3.0f, 1.0f}};
    const fs::path dir = kiri::test::temp_path("no_such_exr_dir");
    fs::remove_all(dir);
    try {
        kiri::render::write_exr_atomic(dir / "out.exr", image);
        FAIL() << "expected an IoError";
    } catch (const kiri::IoError& e) {
        EXPECT_NE(std::string(e.what()).find((dir / "out.exr").string()), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(dir));
    EXPECT_THROW(kiri::render::write_exr_atomic(kiri::test::temp_path("empty.exr"), RadianceImage{}), kiri::IoError);
}

TEST(Exr, NotAnExrIsAnInputError)
{
    const fs::path path = kiri::test::temp_path("not_an_exr.exr");
    std::ofstream(path) << "hello";
    try {
        (void)kiri::render::read_exr(path);
        FAIL() << "expected an InputError";
    } catch (const kiri::InputError& e) {
        EXPECT_EQ(e.file(), path.string());
    }
    fs::remove(path);
}
