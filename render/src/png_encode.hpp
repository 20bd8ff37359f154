#pragma once
// Internal: an 8-bit RGBA PNG encoded with zlib at its fastest level. stb_image_write's own
// deflate took 150 to 220 ms for a 1280x720 frame, a twentieth of a still's render; zlib's
// level 1 over the Sub filter takes a fifth of that, and its files are a fifth smaller.
#include <cstdint>
#include <vector>

#include "kiri/render/image.hpp"

namespace kiri::render::detail {

//! The whole file: signature, IHDR, one IDAT, IEND (rows top to bottom, every row filtered by
//! Sub). An empty vector when zlib fails (it does not for a consistent image).
std::vector<std::uint8_t> encode_png(const Image& image);

}  // namespace kiri::render::detail
