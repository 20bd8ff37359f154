#include "kiri/geometry/particles/attenuation_cpu.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace kiri::geometry {
namespace {

// GL_LINEAR with GL_CLAMP_TO_EDGE along one axis: the two texels and the weight of the second.
struct Taps {
    int a, b;
    double t;
};
Taps taps(double g, int n)
{
    const double x = g - 0.5;
    const double f = std::floor(x);
    const int i = int(std::clamp(f, -1.0, double(n)));
    return {std::clamp(i, 0, n - 1), std::clamp(i + 1, 0, n - 1), std::isfinite(x) ? x - f : 0.0};
}

}  // namespace

double column_log_gain(const LightGrid& g, const Particle& p, double forward, double du, double dv)
{
    const double rho = std::sqrt(du * du + dv * dv);
    if (!(rho < p.radius))
        return 0.0;
    // The column: p's centre + offset + u light, u metres towards the sun. Each plane keeps the
    // part of it on the fog's side (side 1: over a floor; -1: under a top), as particles.frag
    // clips a ray.
    const glm::dvec3 offset = du * g.u_axis + dv * g.v_axis;
    double u0 = -HUGE_VAL, u1 = HUGE_VAL;
    const auto clip = [&](double z, const glm::dvec2& slope, double side) {
        if (!std::isfinite(z))
            return;
        const double above = side * (p.position.z + offset.z - z - glm::dot(slope, glm::dvec2(offset)));
        const double rise = side * (g.light.z - glm::dot(slope, glm::dvec2(g.light)));
        if (rise > 0.0)
            u0 = std::max(u0, -above / rise);
        else if (rise < 0.0)
            u1 = std::min(u1, -above / rise);
        else if (above < 0.0)
            u1 = -HUGE_VAL;
    };
    clip(p.floor, p.floor_slope, 1.0);
    clip(p.top, p.top_slope, -1.0);
    const double share =
        u0 == -HUGE_VAL && u1 == HUGE_VAL ? 1.0 : footprint_ray_share(rho / p.radius, p.radius, u0, u1);
    if (!(share > 0.0))
        return 0.0;
    return footprint_log_gain(rho, p.radius, p.optical_depth * mass_gain(p.above_ground) * share, p.albedo, forward);
}

AttenuationVolume build_attenuation_cpu(const ParticleCloud& cloud, const LightGrid& grid)
{
    AttenuationVolume v{grid, {}};
    const int nx = grid.size[0], ny = grid.size[1], nz = grid.size[2];
    std::vector<double> sum(grid.voxel_count(), 0.0);
    const auto at = [&](int i, int j, int k) { return (std::size_t(k) * ny + j) * nx + i; };
    for (const Particle& p : cloud.particles)
        for_each_deposit(grid, p, cloud.forward_scattering,
                         [&](int i, int j, int k, double log_g) { sum[at(i, j, k)] += log_g; });
    v.log_gamma.resize(sum.size());
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            double column = 0.0;
            for (int k = 0; k < nz; ++k) {
                column += sum[at(i, j, k)];
                v.log_gamma[at(i, j, k)] = float(std::max(column, min_log_gamma));
            }
        }
    return v;
}

double sample_log_gamma(const AttenuationVolume& v, const glm::dvec3& p)
{
    const LightGrid& g = v.grid;
    const glm::dvec3 c = g.to_grid(p);
    const Taps x = taps(c.x, g.size[0]), y = taps(c.y, g.size[1]), z = taps(c.z, g.size[2]);
    const auto at = [&](int i, int j, int k) {
        return double(v.log_gamma[(std::size_t(k) * g.size[1] + j) * g.size[0] + i]);
    };
    double sum = 0.0;
    for (int dk = 0; dk < 2; ++dk)
        for (int dj = 0; dj < 2; ++dj)
            for (int di = 0; di < 2; ++di) {
                const double w = (di ? x.t : 1.0 - x.t) * (dj ? y.t : 1.0 - y.t) * (dk ? z.t : 1.0 - z.t);
                sum += w * at(di ? x.b : x.a, dj ? y.b : y.a, dk ? z.b : z.a);
            }
    return sum;
}

namespace {

// The own footprint's log gain in the four columns a trilinear read at q takes, weighted as the
// read weighs them: from the particle's shadow start on (what the read holds of it), or over the
// whole column.
double own_read_log_gain(const LightGrid& g, const Particle& self, double forward, const glm::dvec3& q,
                         bool whole_column)
{
    const glm::dvec3 c = g.to_grid(q);
    const glm::dvec3 s = g.light_coordinates(self.position);
    const Taps x = taps(c.x, g.size[0]), y = taps(c.y, g.size[1]), z = taps(c.z, g.size[2]);
    double sum = 0.0;
    for (int dj = 0; dj < 2; ++dj)
        for (int di = 0; di < 2; ++di) {
            const int i = di ? x.b : x.a, j = dj ? y.b : y.a;
            const double du = g.column_u(i) - s.x, dv = g.column_v(j) - s.y;
            const double log_g = column_log_gain(g, self, forward, du, dv);
            if (log_g == 0.0)
                continue;
            const int start = std::max(g.shadow_start(s.z, i, j), 0);
            // Depth taps at or beyond the start hold the particle (the prefix sum).
            const double depth = whole_column ? 1.0 : (z.a >= start ? 1.0 - z.t : 0.0) + (z.b >= start ? z.t : 0.0);
            sum += (di ? x.t : 1.0 - x.t) * (dj ? y.t : 1.0 - y.t) * depth * log_g;
        }
    return sum;
}

}  // namespace

double self_log_gamma(const LightGrid& g, const Particle& self, double forward, const glm::dvec3& q)
{
    return own_read_log_gain(g, self, forward, q, false);
}

double own_column_log_gain(const LightGrid& g, const Particle& self, double forward, const glm::dvec3& q)
{
    return own_read_log_gain(g, self, forward, q, true);
}

double billboard_own_share_at(const Particle& self, const glm::dvec3& light, const glm::dvec3& q, double share)
{
    if (!std::isfinite(self.top) || !(self.radius > 0.0))
        return share;
    // q under the top's plane by `under`, the ray towards the sun rising over it at `rise`.
    const double under = self.top + glm::dot(self.top_slope, glm::dvec2(q - self.position)) - q.z;
    const double rise = light.z - glm::dot(self.top_slope, glm::dvec2(light));
    if (!(rise > 0.0))
        return share;
    return share * std::clamp(under / rise / self.radius, 0.0, 1.0);
}

double billboard_log_gamma(const AttenuationVolume& v, const Particle& self, double forward, const glm::dvec3& q,
                           double share)
{
    const double log_gamma = sample_log_gamma(v, q) - self_log_gamma(v.grid, self, forward, q) +
        billboard_own_share_at(self, v.grid.light, q, share) * own_column_log_gain(v.grid, self, forward, q);
    return std::clamp(log_gamma, min_log_gamma, 0.0);
}

double calibrated_own_share(const AttenuationVolume& v, const Particle& self, double forward, double tau_sun)
{
    const glm::dvec3& c = self.position;
    const double others =
        std::clamp(sample_log_gamma(v, c) - self_log_gamma(v.grid, self, forward, c), min_log_gamma, 0.0);
    const double own =
        own_column_log_gain(v.grid, self, forward, c) * billboard_own_share_at(self, v.grid.light, c, 1.0);
    if (!(own < -1e-4) || !(tau_sun >= 0.0 && tau_sun < 1e30))
        return billboard_own_share;
    return std::clamp((-tau_sun - others) / own, min_own_share, max_own_share);
}

double particle_gamma(const AttenuationVolume& v, const ParticleCloud& cloud, std::size_t k)
{
    const Particle& p = cloud.particles[k];
    const double log_gamma =
        sample_log_gamma(v, p.position) - self_log_gamma(v.grid, p, cloud.forward_scattering, p.position);
    return std::exp(std::clamp(log_gamma, min_log_gamma, 0.0));
}

}  // namespace kiri::geometry
