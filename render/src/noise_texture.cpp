#include "noise_texture.hpp"

#include <cmath>
#include <cstdint>
#include <vector>

#include "kiri/geometry/medium/medium.hpp"

namespace kiri::render::detail {

Texture make_noise_texture(int size)
{
    // The medium's noise tile (geometry/src/medium/fog_noise.cpp), so layers and volumes share it.
    const std::vector<float>& tile = geometry::fog_noise_tile(size);
    std::vector<std::uint8_t> texels(tile.size());
    for (std::size_t k = 0; k < tile.size(); ++k)
        texels[k] = std::uint8_t(std::lround(tile[k] * 255.0f));
    Texture t = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(t.get(), 1, GL_R8, size, size);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(t.get(), 0, 0, 0, size, size, GL_RED, GL_UNSIGNED_BYTE, texels.data());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureParameteri(t.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(t.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(t.get(), GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(t.get(), GL_TEXTURE_WRAP_T, GL_REPEAT);
    return t;
}

}  // namespace kiri::render::detail
