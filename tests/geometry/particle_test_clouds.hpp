#pragma once
// Shared by the particle tests: small media and clouds built in code.
#include <cmath>
#include <random>
#include <vector>

#include "kiri/geometry/medium/medium.hpp"
#include "kiri/geometry/particles/particles.hpp"

namespace kiri::test {

//! A flat shell over a square: side x side metres, fog from `bottom` to `top`, full coverage,
//! no noise; the profile is the layers' (top_density at the top) unless `uniform`.
inline geometry::Medium slab_medium(double side = 1000.0, double bottom = 100.0, double top = 300.0,
                                    bool uniform = false, double extinction = 0.02)
{
    geometry::MediumGrid g;
    g.nx = g.ny = 5;
    g.x0 = g.y0 = -0.5 * side;
    g.dx = g.dy = side / 4.0;
    g.bottom.assign(25, bottom);
    g.top.assign(25, top);
    g.floor.assign(25, bottom);
    g.coverage.assign(25, 1.0);
    geometry::MediumOptions o;
    o.extinction = extinction;
    o.top_density = uniform ? 1.0 : 0.1;
    geometry::MediumDetail d;
    d.detail = 0.0;
    return geometry::Medium(std::move(g), o, d);
}

//! n particles uniformly in a ball (deterministic), equal radius and optical depth.
inline geometry::ParticleCloud ball_cloud(int n, double ball_radius, double radius, double tau, double albedo = 0.9,
                                          double forward = 0.23, unsigned seed = 7)
{
    std::mt19937_64 rng(seed);
    const auto u = [&] { return double(rng() >> 11) * 0x1.0p-53; };
    geometry::ParticleCloud c;
    c.forward_scattering = forward;
    while (int(c.particles.size()) < n) {
        const glm::dvec3 p(2.0 * u() - 1.0, 2.0 * u() - 1.0, 2.0 * u() - 1.0);
        if (p.x * p.x + p.y * p.y + p.z * p.z > 1.0)
            continue;
        c.particles.push_back({p * ball_radius + glm::dvec3(0.0, 0.0, 1000.0), radius, tau, albedo});
    }
    return c;
}

}  // namespace kiri::test
