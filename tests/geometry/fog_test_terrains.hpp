#pragma once
// Analytic terrains for the fog tests: heightfields sampled from closed-form functions.
#include <cmath>
#include <functional>

#include "kiri/geometry/terrain/heightfield.hpp"

namespace kiri::test {

inline geometry::Heightfield make_heightfield(int nx, int ny, double d, double x0, double y0,
                                              const std::function<double(double, double)>& z)
{
    geometry::Heightfield hf;
    hf.nx = nx;
    hf.ny = ny;
    hf.dx = hf.dy = d;
    hf.x0 = x0;
    hf.y0 = y0;
    hf.z.resize(std::size_t(nx) * ny);
    hf.valid.assign(hf.z.size(), 1);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
            hf.z[std::size_t(j) * nx + i] = z(x0 + i * d, y0 + j * d);
    return hf;
}

// Hills and a sharp ridge in local coordinates (metres), 2 km square around the origin.
inline double hills(double x, double y)
{
    return 400.0 + 80.0 * std::sin(x / 300.0) * std::cos(y / 400.0) + 150.0 * std::exp(-std::abs(x - 200.0) / 60.0);
}

}  // namespace kiri::test
