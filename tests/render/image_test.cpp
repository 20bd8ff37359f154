#include <gtest/gtest.h>

#include "temp_path.hpp"

#include <filesystem>
#include <random>

#include "kiri/geometry/core/error.hpp"
#include "kiri/render/image.hpp"

namespace fs = std::filesystem;

namespace {

// Writes the image, reads it back and expects every byte; the file's size.
std::uintmax_t expect_round_trip(const kiri::render::Image& image, const std::string& name)
{
    const fs::path path = kiri::test::temp_path(name);
    kiri::render::write_png_atomic(path, image);
    const kiri::render::Image back = kiri::render::read_png(path);
    EXPECT_EQ(back.width, image.width);
    EXPECT_EQ(back.height, image.height);
    EXPECT_EQ(back.rgba, image.rgba);
    const std::uintmax_t size = fs::file_size(path);
    fs::remove(path);
    return size;
}

}  // namespace

TEST(Png, RoundTripsExactly)
{
    kiri::render::Image image{3, 2, {}};
    for (int k = 0; k < 3 * 2 * 4; ++k)
        image.rgba.push_back(std::uint8_t(k * 11));
    expect_round_trip(image, "image_test.png");
}

// kiri encodes its PNGs itself (zlib's deflate, rows filtered by Sub); stb_image decodes them:
// every byte back, where a filter's differences wrap below 0 and over 255, at a width that is
// no multiple of anything, with the alpha channel varying.
TEST(Png, RoundTripsEveryByteOfALargeNoisyFrame)
{
    kiri::render::Image image{333, 77, std::vector<std::uint8_t>(333 * 77 * 4)};
    std::mt19937 rng(3);
    for (std::size_t k = 0; k < image.rgba.size(); ++k)  // noise over a gradient: both kinds of row
        image.rgba[k] = std::uint8_t(k % 7 == 0 ? rng() : (k / 4) % 333);
    EXPECT_LT(expect_round_trip(image, "image_test_large.png"), image.rgba.size());  // compressed
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
