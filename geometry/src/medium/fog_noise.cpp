#include <cmath>
#include <map>
#include <mutex>
#include <random>

#include "kiri/geometry/medium/medium.hpp"

namespace kiri::geometry {
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
    float at(int i, int j) const
    {
        return v[std::size_t(((j % cells) + cells) % cells) * cells + ((i % cells) + cells) % cells];
    }
    double sample(double x, double y) const  // x, y in lattice cells
    {
        const int i = int(std::floor(x)), j = int(std::floor(y));
        double fx = x - i, fy = y - j;
        fx = fx * fx * (3.0 - 2.0 * fx);
        fy = fy * fy * (3.0 - 2.0 * fy);
        const double a = at(i, j) + (at(i + 1, j) - at(i, j)) * fx;
        const double b = at(i, j + 1) + (at(i + 1, j + 1) - at(i, j + 1)) * fx;
        return a + (b - a) * fy;
    }
};

std::vector<float> make_tile(int size)
{
    std::mt19937 rng(20081123u);
    const Lattice octaves[3] = {Lattice(8, rng), Lattice(16, rng), Lattice(32, rng)};
    const double weights[3] = {0.5, 0.3, 0.2};
    std::vector<float> tile(std::size_t(size) * size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            double n = 0.0;
            for (int o = 0; o < 3; ++o)
                n += weights[o] *
                    octaves[o].sample(double(x) / size * octaves[o].cells, double(y) / size * octaves[o].cells);
            tile[std::size_t(y) * size + x] = float(std::fmin(std::fmax(n, 0.0), 1.0));
        }
    return tile;
}

}  // namespace

const std::vector<float>& fog_noise_tile(int size)
{
    static std::mutex mutex;
    static std::map<int, std::vector<float>> tiles;  // node-based: references stay valid
    if (size < 1)
        size = 1;
    const std::lock_guard lock(mutex);
    auto it = tiles.find(size);
    if (it == tiles.end())
        it = tiles.emplace(size, make_tile(size)).first;
    return it->second;
}

double sample_fog_noise(double s, double t, int size)
{
    if (!std::isfinite(s) || !std::isfinite(t))
        return 0.5;
    // The default tile without the cache's lock: the reference ray marcher samples it from
    // every thread millions of times.
    static const std::vector<float>& default_tile = fog_noise_tile(256);
    const std::vector<float>& tile = size == 256 ? default_tile : fog_noise_tile(size);
    // GL_LINEAR with GL_REPEAT: texel centres at (i + 0.5) / size.
    const double x = s * size - 0.5, y = t * size - 0.5;
    const double fx0 = std::floor(x), fy0 = std::floor(y);
    const double fx = x - fx0, fy = y - fy0;
    auto wrap = [size](double i) { return int(i - std::floor(i / size) * size); };
    const int i0 = wrap(fx0), j0 = wrap(fy0), i1 = (i0 + 1) % size, j1 = (j0 + 1) % size;
    auto at = [&](int i, int j) { return double(tile[std::size_t(j) * size + i]); };
    const double a = at(i0, j0) + (at(i1, j0) - at(i0, j0)) * fx;
    const double b = at(i0, j1) + (at(i1, j1) - at(i0, j1)) * fx;
    return a + (b - a) * fy;
}

}  // namespace kiri::geometry
