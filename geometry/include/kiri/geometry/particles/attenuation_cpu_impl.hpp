#pragma once
// The template of attenuation_cpu.hpp (one loop shared by the deposit and its tests).
#include <algorithm>
#include <cmath>

#include "kiri/geometry/particles/particle_footprint.hpp"

namespace kiri::geometry {

template <typename Fn>
void for_each_deposit(const LightGrid& grid, const Particle& p, double forward, Fn&& fn)
{
    const glm::dvec3 q = grid.light_coordinates(p.position);
    const double r = p.radius;
    if (!(r > 0.0) || !std::isfinite(r))
        return;
    // Columns whose centre lies within r of the axis: centre u = u0 + (i + 0.5) du.
    const int i0 = std::max(0, int(std::ceil((q.x - r - grid.origin.x) / grid.voxel.x - 0.5)));
    const int i1 = std::min(grid.size[0] - 1, int(std::floor((q.x + r - grid.origin.x) / grid.voxel.x - 0.5)));
    const int j0 = std::max(0, int(std::ceil((q.y - r - grid.origin.y) / grid.voxel.y - 0.5)));
    const int j1 = std::min(grid.size[1] - 1, int(std::floor((q.y + r - grid.origin.y) / grid.voxel.y - 0.5)));
    for (int j = j0; j <= j1; ++j) {
        const double dv = grid.column_v(j) - q.y;
        for (int i = i0; i <= i1; ++i) {
            const double du = grid.column_u(i) - q.x;
            const double rho = std::sqrt(du * du + dv * dv);
            if (!(rho < r))
                continue;
            const int k = grid.shadow_start(q.z, i, j);
            if (k >= grid.size[2])
                continue;
            fn(i, j, std::max(k, 0), column_log_gain(grid, p, forward, du, dv));
        }
    }
}

}  // namespace kiri::geometry
