#include <algorithm>
#include <cmath>
#include <limits>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/medium/medium.hpp"

namespace kiri::geometry {
namespace {

double smoothstep(double a, double b, double x)
{
    const double t = std::clamp((x - a) / (b - a), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

// The layers' per-layer shift of the noise (render/shaders/layers.frag), per layer index.
constexpr double layer_shift_x = 0.137, layer_shift_y = 0.071;

}  // namespace

MediumDetail medium_detail(const MediumOptions& medium)
{
    MediumDetail d;
    d.detail = medium.detail;
    d.detail_scale = medium.detail_scale;
    d.layers = medium.detail_layers;
    d.wind = medium.wind;
    d.time = medium.time;
    d.dissipation_half_life = medium.dissipation_half_life;
    return d;
}

void validate_medium_options(const MediumOptions& o, const std::string& label) { check_fields(o, label, "/medium"); }

Medium::Medium(MediumGrid grid, const MediumOptions& options, const MediumDetail& detail)
    : grid_(std::move(grid)), options_(options), detail_(detail)
{
    const std::size_t n = std::size_t(std::max(grid_.nx, 0)) * std::size_t(std::max(grid_.ny, 0));
    if (grid_.nx < 2 || grid_.ny < 2 || grid_.floor.size() != n || grid_.bottom.size() != n || grid_.top.size() != n ||
        grid_.coverage.size() != n || !(grid_.dx > 0.0) || !(grid_.dy > 0.0))
        throw InputError("", "medium", "the grid needs at least 2 x 2 samples and nx ny values in each array");
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t k = 0; k < n; ++k) {
        grid_.coverage[k] = std::clamp(std::isfinite(grid_.coverage[k]) ? grid_.coverage[k] : 0.0, 0.0, 1.0);
        if (grid_.coverage[k] > 0.0 && grid_.top[k] > grid_.floor[k]) {
            lo = std::min(lo, grid_.floor[k]);
            hi = std::max(hi, grid_.top[k]);
            max_density_ = std::max(max_density_, grid_.coverage[k]);
        }
    }
    if (hi < lo)  // no fog anywhere: an empty box at the grid's centre
        lo = hi = 0.0;
    corners_.resize(n);
    for (std::size_t k = 0; k < n; ++k)
        corners_[k] = {grid_.floor[k], grid_.bottom[k], grid_.top[k], grid_.coverage[k]};
    bounds_.min = {grid_.x0, grid_.y0, lo};
    bounds_.max = {grid_.x0 + (grid_.nx - 1) * grid_.dx, grid_.y0 + (grid_.ny - 1) * grid_.dy, hi};
}

MediumColumn Medium::column(double x, double y) const
{
    if (grid_.nx < 2 || !std::isfinite(x) || !std::isfinite(y))
        return {};
    const double gx = std::clamp((x - grid_.x0) / grid_.dx, 0.0, double(grid_.nx - 1));
    const double gy = std::clamp((y - grid_.y0) / grid_.dy, 0.0, double(grid_.ny - 1));
    const int i = std::min(int(gx), grid_.nx - 2), j = std::min(int(gy), grid_.ny - 2);
    const double fx = gx - i, fy = gy - j;
    const glm::dvec4* c = &corners_[std::size_t(j) * grid_.nx + i];
    const glm::dvec4 a = c[0] + (c[1] - c[0]) * fx;
    const glm::dvec4 b = c[grid_.nx] + (c[grid_.nx + 1] - c[grid_.nx]) * fx;
    const glm::dvec4 v = a + (b - a) * fy;
    const bool outside = x < grid_.x0 || y < grid_.y0 || x > bounds_.max.x || y > bounds_.max.y;
    return {v.x, v.y, v.z, outside ? 0.0 : v.w};
}

double Medium::detail_factor(double x, double y, double h) const
{
    if (detail_.detail <= 0.0)
        return 1.0;
    const double tile = 8.0 * detail_.detail_scale;
    const double layer = h * detail_.layers;
    const double s = (x + detail_.noise_shift.x - detail_.wind.x * detail_.time) / tile + layer * layer_shift_x;
    const double t = (y + detail_.noise_shift.y - detail_.wind.y * detail_.time) / tile + layer * layer_shift_y;
    return 1.0 - detail_.detail + detail_.detail * smoothstep(0.25, 0.75, sample_fog_noise(s, t));
}

double Medium::dissipation(double h) const
{
    if (detail_.dissipation_half_life <= 0.0 || detail_.time <= 0.0)
        return 1.0;
    return std::exp2(-detail_.time / detail_.dissipation_half_life * (1.0 + std::clamp(h, 0.0, 1.0)));
}

double Medium::density(const glm::dvec3& p) const
{
    const MediumColumn c = column(p.x, p.y);
    if (c.coverage <= 0.0 || !(p.z >= c.floor) || !(p.z <= c.top) || !(c.top > c.bottom))
        return 0.0;
    const double h = std::clamp((p.z - c.bottom) / (c.top - c.bottom), 0.0, 1.0);
    const double profile = 1.0 - (1.0 - options_.top_density) * h;
    return c.coverage * profile * detail_factor(p.x, p.y, h) * dissipation(h);
}

double Medium::height_fraction(const glm::dvec3& p) const
{
    const MediumColumn c = column(p.x, p.y);
    if (!(c.top > c.bottom))
        return 0.0;
    return std::clamp((p.z - c.bottom) / (c.top - c.bottom), 0.0, 1.0);
}

double Medium::shell_volume() const
{
    // Trapezoidal rule over the grid of coverage (top - floor)+.
    double sum = 0.0;
    for (int j = 0; j < grid_.ny; ++j)
        for (int i = 0; i < grid_.nx; ++i) {
            const std::size_t k = std::size_t(j) * grid_.nx + i;
            const double w = (i == 0 || i == grid_.nx - 1 ? 0.5 : 1.0) * (j == 0 || j == grid_.ny - 1 ? 0.5 : 1.0);
            sum += w * grid_.coverage[k] * std::max(grid_.top[k] - grid_.floor[k], 0.0);
        }
    return sum * grid_.dx * grid_.dy;
}

}  // namespace kiri::geometry
