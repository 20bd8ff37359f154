#pragma once
// Test helpers shared by the lighting tests: a uniform slab of fog, light from the sky alone, a
// relative comparison of colours and Gauss-Legendre quadrature.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "kiri/geometry/medium/fog_lighting.hpp"
#include "kiri/geometry/medium/medium.hpp"

namespace kiri::test {

// A slab of fog (no noise unless `detail`) between z = bottom and z = top over
// [x0, x0 + 2 half] x [-half, half], on a 3 x 3 grid.
inline geometry::Medium slab_medium(double bottom, double top, double sigma, double albedo, double g, double half,
                                    double x0, double top_density = 1.0, double detail = 0.0)
{
    geometry::MediumGrid grid;
    grid.nx = grid.ny = 3;
    grid.x0 = x0;
    grid.y0 = -half;
    grid.dx = grid.dy = half;
    grid.floor.assign(9, bottom);
    grid.bottom.assign(9, bottom);
    grid.top.assign(9, top);
    grid.coverage.assign(9, 1.0);
    geometry::MediumOptions o;
    o.extinction = sigma;
    o.albedo = albedo;
    o.anisotropy = g;
    o.top_density = top_density;
    geometry::MediumDetail d;
    d.detail = detail;
    d.detail_scale = 150.0;
    return geometry::Medium(std::move(grid), o, d);
}

// Lit by the sky alone: no sun, no shadows.
inline geometry::FogLighting sky_only()
{
    geometry::FogLighting l;
    l.sun_radiance = glm::dvec3(0.0);
    l.ambient = glm::dvec3(0.2, 0.3, 0.4);
    l.terrain_shadows = false;
    l.fog_shadows = false;
    return l;
}

// Each channel of a within tol of b's, relatively.
inline void expect_rel(const glm::dvec3& a, const glm::dvec3& b, double tol)
{
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(a[c], b[c], tol * std::abs(b[c]) + 1e-15) << "channel " << c;
}

// Gauss-Legendre nodes and weights on [-1, 1] (Newton on the Legendre polynomial).
inline std::vector<std::pair<double, double>> gauss_legendre(int n)
{
    std::vector<std::pair<double, double>> nodes;
    for (int i = 0; i < n; ++i) {
        double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5)), dp = 0.0;
        for (int it = 0; it < 100; ++it) {
            double p0 = 1.0, p1 = x;
            for (int k = 2; k <= n; ++k) {
                const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (x * p1 - p0) / (x * x - 1.0);
            const double dx = p1 / dp;
            x -= dx;
            if (std::abs(dx) < 1e-15)
                break;
        }
        nodes.emplace_back(x, 2.0 / ((1.0 - x * x) * dp * dp));
    }
    return nodes;
}

}  // namespace kiri::test
