#include "noise_texture.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace kiri::render::detail {
namespace {

// Periodic value noise: a random lattice of `cells` x `cells` values, smoothly interpolated.
struct Lattice {
    int cells;
    std::vector<float> v;
    Lattice(int n, std::mt19937& rng) : cells(n), v(std::size_t(n) * n)
    {
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        for (float& x : v)
            x = u(rng);
    }
    float at(int i, int j) const { return v[std::size_t(((j % cells) + cells) % cells) * cells + ((i % cells) + cells) % cells]; }
    float sample(double x, double y) const  // x, y in lattice cells
    {
        const int i = int(std::floor(x)), j = int(std::floor(y));
        double fx = x - i, fy = y - j;
        fx = fx * fx * (3.0 - 2.0 * fx);
        fy = fy * fy * (3.0 - 2.0 * fy);
        const double a = at(i, j) + (at(i + 1, j) - at(i, j)) * fx;
        const double b = at(i, j + 1) + (at(i + 1, j + 1) - at(i, j + 1)) * fx;
        return float(a + (b - a) * fy);
    }
};

}  // namespace

Texture make_noise_texture(int size)
{
    std::mt19937 rng(20081123u);
    const Lattice octaves[3] = {Lattice(8, rng), Lattice(16, rng), Lattice(32, rng)};
    const double weights[3] = {0.5, 0.3, 0.2};
    std::vector<std::uint8_t> texels(std::size_t(size) * size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            double n = 0.0;
            for (int o = 0; o < 3; ++o)
                n += weights[o] * octaves[o].sample(double(x) / size * octaves[o].cells, double(y) / size * octaves[o].cells);
            texels[std::size_t(y) * size + x] = std::uint8_t(std::lround(std::clamp(n, 0.0, 1.0) * 255.0));
        }
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
