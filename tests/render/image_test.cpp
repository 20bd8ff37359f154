#include <gtest/gtest.h>

#include "temp_path.hpp"

#include <filesystem>

#include "kiri/geometry/core/error.hpp"
#include "kiri/render/image.hpp"

namespace fs = std::filesystem;

TEST(Png, RoundTripsExactly)
{
    kiri::render::Image image{3, 2, {}};
    for (int k = 0; k < 3 * 2 * 4; ++k)
        image.rgba.push_back(std::uint8_t(k * 11));
    const fs::path path = kiri::test::temp_path("image_test.png");
    kiri::render::write_png_atomic(path, image);
    const kiri::render::Image back = kiri::render::read_png(path);
    EXPECT_EQ(back.width, 3);
    EXPECT_EQ(back.height, 2);
    EXPECT_EQ(back.rgba, image.rgba);
    fs::remove(path);
}

TEST(Png, UnwritablePathThrowsAndLeavesNothing)
{
    const kiri::render::Image image{1, 1, {1, 2, 3, 4}};
    const fs::path dir = kiri::test::temp_path("no_such_dir");
    fs::remove_all(dir);
    try {
        kiri::render::write_png_atomic(dir / "out.png", image);
        FAIL() << "expected an IoError";
    } catch (const kiri::IoError& e) {
        EXPECT_NE(std::string(e.what()).find((dir / "out.png").string()), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(dir));
}

TEST(Png, NotAPngIsAnInputError)
{
    const fs::path path = kiri::test::temp_path("not_a_png.png");
    {
        std::FILE* f = std::fopen(path.c_str(), "w");
        std::fputs("hello", f);
        std::fclose(f);
    }
    EXPECT_THROW(kiri::render::read_png(path), kiri::InputError);
    fs::remove(path);
}
