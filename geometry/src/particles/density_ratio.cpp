#include "kiri/geometry/particles/density_ratio.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/parallel_rows.hpp"
#include "kiri/geometry/medium/medium.hpp"
#include "kiri/geometry/particles/particle_footprint.hpp"
#include "kiri/geometry/particles/particles.hpp"

namespace kiri::geometry {
namespace {

// Whether p lies on the fog's side of a particle's floor and top planes (as a billboard clips
// its ray at them).
bool within_ball_planes(const Particle& b, const glm::dvec3& p)
{
    const glm::dvec2 off(p.x - b.position.x, p.y - b.position.y);
    if (std::isfinite(b.floor) && p.z < b.floor + glm::dot(b.floor_slope, off))
        return false;
    if (std::isfinite(b.top) && p.z > b.top + glm::dot(b.top_slope, off))
        return false;
    return true;
}

// GL_LINEAR + GL_CLAMP_TO_EDGE along one axis of n texels at coordinate g (in texels, centres
// at k + 1/2): the two texels and the second's weight.
struct RatioTaps {
    int a, b;
    double w;
};
RatioTaps ratio_taps(double g, int n)
{
    const double x = g - 0.5, f = std::floor(x);
    const int i = int(std::clamp(f, -1.0, double(n)));
    return {std::clamp(i, 0, n - 1), std::clamp(i + 1, 0, n - 1), x - f};
}

// Each column's floor and top: the Medium's where it has fog; beside the fog (breadth first, a
// ring a pass, each taking the mean of its filled neighbours) out to `reach`, the fog's beside
// it; the rest 1 m over their floor. Returns the thickest column of fog.
double shell_columns(DensityRatioGrid& g, const Medium& medium, double reach)
{
    const std::size_t columns = std::size_t(g.nx) * g.ny;
    g.floor.assign(columns, 0.0f);
    g.top.assign(columns, 0.0f);
    std::vector<char> filled(columns, 0);
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            const std::size_t c = std::size_t(j) * g.nx + i;
            const MediumColumn m = medium.column(g.x0 + (i + 0.5) * g.dx, g.y0 + (j + 0.5) * g.dy);
            g.floor[c] = float(m.floor);
            g.top[c] = float(std::max(m.top, m.floor + 1.0));
            filled[c] = m.coverage > 0.0 && m.top > m.floor;
        }
    double thickest = 0.0;
    for (std::size_t c = 0; c < columns; ++c)
        if (filled[c])
            thickest = std::max(thickest, double(g.top[c]) - double(g.floor[c]));
    const int rings = int(std::ceil(reach / std::min(g.dx, g.dy)));
    for (int ring = 0; ring < rings; ++ring) {
        std::vector<char> next = filled;
        std::vector<float> floor = g.floor, top = g.top;
        bool grew = false;
        for (int j = 0; j < g.ny; ++j)
            for (int i = 0; i < g.nx; ++i) {
                const std::size_t c = std::size_t(j) * g.nx + i;
                if (filled[c])
                    continue;
                double f = 0.0, t = 0.0;
                int n = 0;
                for (int dj = -1; dj <= 1; ++dj)
                    for (int di = -1; di <= 1; ++di) {
                        const int a = i + di, b = j + dj;
                        if (a < 0 || b < 0 || a >= g.nx || b >= g.ny)
                            continue;
                        const std::size_t o = std::size_t(b) * g.nx + a;
                        if (filled[o]) {
                            f += g.floor[o];
                            t += g.top[o];
                            ++n;
                        }
                    }
                if (n > 0) {
                    floor[c] = float(f / n);
                    top[c] = float(t / n);
                    next[c] = 1;
                    grew = true;
                }
            }
        filled.swap(next);
        g.floor.swap(floor);
        g.top.swap(top);
        if (!grew)
            break;
    }
    return thickest;
}

}  // namespace

DensityRatioGrid density_ratio_grid(const ParticleCloud& cloud, const Medium& medium,
                                    const DensityRatioOptions& options)
{
    DensityRatioGrid g;
    const MediumGrid& mg = medium.grid();
    if (cloud.particles.empty() || mg.nx < 2 || mg.ny < 2 || options.min_levels < 1 ||
        options.max_levels < options.min_levels || options.max_side < 1 ||
        cloud.extinction != medium.options().extinction || cloud.albedo != medium.options().albedo)
        return g;
    double smallest = 1e300, largest = 0.0;
    for (const Particle& p : cloud.particles)
        if (p.radius > 0.0 && std::isfinite(p.radius)) {
            smallest = std::min(smallest, p.radius);
            largest = std::max(largest, p.radius);
        }
    if (!(smallest < 1e300))
        return g;
    const double width = (mg.nx - 1) * mg.dx, depth = (mg.ny - 1) * mg.dy;
    const double side =
        std::max({std::min({mg.dx, mg.dy, 0.5 * smallest}), width / options.max_side, depth / options.max_side});
    g.nx = std::max(1, int(std::ceil(width / side)));
    g.ny = std::max(1, int(std::ceil(depth / side)));
    g.x0 = mg.x0;
    g.y0 = mg.y0;
    g.dx = width / g.nx;
    g.dy = depth / g.ny;
    g.max_ratio = options.max_ratio;
    const std::size_t columns = std::size_t(g.nx) * g.ny;
    const double thickest = shell_columns(g, medium, largest);
    g.levels = std::clamp(int(std::ceil(thickest / (0.2 * smallest))), options.min_levels, options.max_levels);
    const auto cell_z = [&](std::size_t c, int l) {
        return double(g.floor[c]) + (l + 0.5) / g.levels * (double(g.top[c]) - double(g.floor[c]));
    };
    // Each row of cells gathers the balls that reach it (lists per row: no two threads write a
    // cell, and the sums come out the same on any number of threads).
    std::vector<std::vector<std::uint32_t>> rows(std::size_t(g.ny));
    for (std::size_t k = 0; k < cloud.particles.size(); ++k) {
        const Particle& b = cloud.particles[k];
        if (!(b.radius > 0.0) || !(b.optical_depth > 0.0) || !std::isfinite(b.radius) || !std::isfinite(b.position.x) ||
            !std::isfinite(b.position.y) || !std::isfinite(b.position.z))
            continue;
        const int j0 = std::max(0, int(std::floor((b.position.y - b.radius - g.y0) / g.dy - 0.5)));
        const int j1 = std::min(g.ny - 1, int(std::ceil((b.position.y + b.radius - g.y0) / g.dy - 0.5)));
        for (int j = j0; j <= j1; ++j)
            rows[std::size_t(j)].push_back(std::uint32_t(k));
    }
    g.balls.assign(columns * g.levels, 0.0f);
    detail::for_rows_in_parallel(options.threads, g.ny, [&](auto next_row) {
        std::vector<double> sum(std::size_t(g.nx) * g.levels);
        for (int j = next_row(); j < g.ny; j = next_row()) {
            const double y = g.y0 + (j + 0.5) * g.dy;
            std::fill(sum.begin(), sum.end(), 0.0);
            for (std::uint32_t k : rows[std::size_t(j)]) {
                const Particle& b = cloud.particles[k];
                const double tau = std::isfinite(b.optical_depth) ? b.optical_depth * mass_gain(b.above_ground) : 1e30;
                const int i0 = std::max(0, int(std::floor((b.position.x - b.radius - g.x0) / g.dx - 0.5)));
                const int i1 = std::min(g.nx - 1, int(std::ceil((b.position.x + b.radius - g.x0) / g.dx - 0.5)));
                for (int i = i0; i <= i1; ++i) {
                    const std::size_t c = std::size_t(j) * g.nx + i;
                    const glm::dvec2 across(g.x0 + (i + 0.5) * g.dx - b.position.x, y - b.position.y);
                    const double rho2 = glm::dot(across, across);
                    if (!(rho2 < b.radius * b.radius))
                        continue;
                    for (int l = 0; l < g.levels; ++l) {
                        const glm::dvec3 p(b.position.x + across.x, y, cell_z(c, l));
                        const double dz = p.z - b.position.z;
                        const double q = std::sqrt(rho2 + dz * dz);
                        if (q < b.radius && within_ball_planes(b, p))
                            sum[std::size_t(l) * g.nx + i] += ball_density(q, b.radius, tau);
                    }
                }
            }
            for (int l = 0; l < g.levels; ++l)
                for (int i = 0; i < g.nx; ++i)
                    g.balls[(std::size_t(l) * g.ny + j) * g.nx + i] = float(sum[std::size_t(l) * g.nx + i]);
        }
    });
    return g;
}

double ball_sum_at(const DensityRatioGrid& g, double x, double y, double h)
{
    if (g.empty() || !std::isfinite(x) || !std::isfinite(y) || !std::isfinite(h))
        return 0.0;
    const RatioTaps tx = ratio_taps((x - g.x0) / g.dx, g.nx), ty = ratio_taps((y - g.y0) / g.dy, g.ny);
    const RatioTaps tl = ratio_taps(h * g.levels, g.levels);
    const std::size_t slice = std::size_t(g.nx) * g.ny;
    const auto bilinear = [&](const float* v) {
        const auto at = [&](int i, int j) { return double(v[std::size_t(j) * g.nx + i]); };
        return (1.0 - ty.w) * ((1.0 - tx.w) * at(tx.a, ty.a) + tx.w * at(tx.b, ty.a)) +
            ty.w * ((1.0 - tx.w) * at(tx.a, ty.b) + tx.w * at(tx.b, ty.b));
    };
    return (1.0 - tl.w) * bilinear(&g.balls[tl.a * slice]) + tl.w * bilinear(&g.balls[tl.b * slice]);
}

double density_ratio_at(const DensityRatioGrid& g, const Medium& medium, double x, double y, double z)
{
    if (g.empty())
        return 0.0;
    const double sigma = medium.extinction({x, y, z});
    if (!(sigma > 0.0))
        return 0.0;
    const MediumColumn c = medium.column(x, y);
    const double h = c.top > c.floor ? (z - c.floor) / (c.top - c.floor) : 0.0;
    const double balls = ball_sum_at(g, x, y, h);
    return balls > 0.0 ? std::min(sigma / balls, g.max_ratio) : g.max_ratio;
}

}  // namespace kiri::geometry
