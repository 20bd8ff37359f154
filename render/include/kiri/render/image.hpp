#pragma once
//! \file image.hpp
//! 8-bit RGBA images, rows top to bottom, and atomic PNG writing.
#include <cstdint>
#include <filesystem>
#include <vector>

namespace kiri::render {

struct Image {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;  //!< width * height * 4, row 0 at the top
};

//! Linear radiance (RGBA float), rows top to bottom: the frame before its tone mapping.
struct RadianceImage {
    int width = 0, height = 0;
    std::vector<float> rgba;  //!< width * height * 4, row 0 at the top
};

//! A multisampled frame's samples before the resolve: per pixel (rows top to bottom) its
//! `samples` samples' linear radiance in turn, and where each sample lies in its pixel.
struct RadianceSamples {
    int width = 0, height = 0, samples = 1;
    std::vector<float> rgba;     //!< ((y * width + x) * samples + s) * 4
    std::vector<float> offsets;  //!< sample s at (offsets[2 s], offsets[2 s + 1]) pixels from the
                                 //!< centre, x right, y down (the image's rows)
};

//! Writes to a temporary file beside path, then renames it: no partial PNG is ever left.
//! \throw kiri::IoError naming the path when it cannot be written.
void write_png_atomic(const std::filesystem::path& path, const Image& image);
//! \throw kiri::InputError when the file is not a readable PNG.
Image read_png(const std::filesystem::path& path);

}  // namespace kiri::render
