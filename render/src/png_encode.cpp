#include "png_encode.hpp"

#include <cstddef>
#include <string_view>

#include <zlib.h>

namespace kiri::render::detail {
namespace {

void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v)
{
    for (int shift = 24; shift >= 0; shift -= 8)
        out.push_back(std::uint8_t(v >> shift));
}

// A chunk: its length, type and data, and the CRC-32 of type and data (PNG spec 5.3).
void put_chunk(std::vector<std::uint8_t>& out, std::string_view type, const std::uint8_t* data, std::size_t size)
{
    put_u32(out, std::uint32_t(size));
    const std::size_t type_at = out.size();
    out.insert(out.end(), type.begin(), type.end());
    out.insert(out.end(), data, data + size);
    const uLong crc = crc32(crc32(0L, Z_NULL, 0), out.data() + type_at, uInt(out.size() - type_at));
    put_u32(out, std::uint32_t(crc));
}

}  // namespace

std::vector<std::uint8_t> encode_png(const Image& image)
{
    const std::size_t row = std::size_t(image.width) * 4, rows = std::size_t(image.height);
    // Each row behind its filter byte, 1 (Sub): a byte less the same channel of the pixel to
    // its left, which turns the frames' smooth gradients into runs of small numbers.
    std::vector<std::uint8_t> filtered((row + 1) * rows);
    for (std::size_t y = 0; y < rows; ++y) {
        const std::uint8_t* in = image.rgba.data() + y * row;
        std::uint8_t* line = filtered.data() + y * (row + 1);
        line[0] = 1;
        for (std::size_t i = 0; i < row; ++i)
            line[1 + i] = std::uint8_t(in[i] - (i >= 4 ? in[i - 4] : 0));
    }
    uLongf packed_size = compressBound(uLong(filtered.size()));
    std::vector<std::uint8_t> packed(packed_size);
    if (compress2(packed.data(), &packed_size, filtered.data(), uLong(filtered.size()), 1) != Z_OK)
        return {};

    std::vector<std::uint8_t> out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    out.reserve(out.size() + packed_size + 64);
    std::vector<std::uint8_t> header;
    put_u32(header, std::uint32_t(image.width));
    put_u32(header, std::uint32_t(image.height));
    header.insert(header.end(), {8, 6, 0, 0, 0});  // 8 bits, RGBA, deflate, filtered by row, not interlaced
    put_chunk(out, "IHDR", header.data(), header.size());
    put_chunk(out, "IDAT", packed.data(), packed_size);
    put_chunk(out, "IEND", nullptr, 0);
    return out;
}

}  // namespace kiri::render::detail
