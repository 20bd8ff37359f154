#include "kiri/geometry/terrain/ground.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>

namespace kiri::geometry {
namespace {

double ease_in_out(double t)
{
    t = std::clamp(t, 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

// Linear on the triangles of cell (i, j), split along (i, j)-(i + 1, j + 1), at cell
// coordinates (s, r) in [0, 1]^2; z(i, j) gives the samples.
template <class Z>
double triangle_height(int i, int j, double s, double r, Z&& z)
{
    const double z00 = z(i, j), z11 = z(i + 1, j + 1);
    if (s >= r)
        return z00 + s * (z(i + 1, j) - z00) + r * (z11 - z(i + 1, j));
    return z00 + r * (z(i, j + 1) - z00) + s * (z11 - z(i, j + 1));
}

template <class Z>
double clamped_grid_height(const Heightfield& hf, double x, double y, Z&& z)
{
    if (hf.nx < 2 || hf.ny < 2)
        return hf.z.empty() ? 0.0 : z(0, 0);
    const double fx = std::clamp((x - hf.x0) / hf.dx, 0.0, double(hf.nx - 1));
    const double fy = std::clamp((y - hf.y0) / hf.dy, 0.0, double(hf.ny - 1));
    const int i = std::min(int(fx), hf.nx - 2), j = std::min(int(fy), hf.ny - 2);
    return triangle_height(i, j, fx - i, fy - j, z);
}

}  // namespace

double grid_height(const Heightfield& hf, double x, double y)
{
    return clamped_grid_height(hf, x, y, [&](int i, int j) { return hf.at(i, j); });
}

std::optional<double> sea_level(const Heightfield& hf)
{
    std::size_t valid = 0, below = 0, zero = 0, above = 0;
    double lowest = 0.0;
    for (std::size_t k = 0; k < hf.z.size(); ++k) {
        if (!hf.valid.empty() && !hf.valid[k])
            continue;
        ++valid;
        below += hf.z[k] <= 0.0;
        above += hf.z[k] > 0.0;
        zero += hf.z[k] == 0.0;
        lowest = std::min(lowest, hf.z[k]);
    }
    if (valid == 0 || double(below) < 0.02 * double(valid) || double(above) < 0.02 * double(valid))
        return std::nullopt;
    if (double(zero) >= 0.01 * double(valid) || lowest < -500.0)
        return 0.0;
    return std::nullopt;
}

Ground::Ground(const Heightfield& hf, bool surround) : hf_(hf), surround_(surround), sea_(geometry::sea_level(hf))
{
    if (hf.z.empty())
        return;
    z_min_ = z_max_ = sample(0, 0);
    for (int j = 0; j < hf.ny; ++j)
        for (int i = 0; i < hf.nx; ++i) {
            z_min_ = std::min(z_min_, sample(i, j));
            z_max_ = std::max(z_max_, sample(i, j));
        }
    const auto edge = [&](double start, double step, int n, auto&& z) {
        Edge e;
        e.start = start;
        e.step = step;
        for (int k = 0; k < n; ++k) {
            e.z.push_back(z(k));
            e.integral.push_back(k == 0 ? 0.0 : e.integral.back() + 0.5 * step * (e.z[k - 1] + e.z[k]));
        }
        return e;
    };
    const int in_x = std::min(1, hf.nx - 1), in_y = std::min(1, hf.ny - 1);  // the row inside the edge
    south_ = {edge(hf.x0, hf.dx, hf.nx, [&](int i) { return sample(i, 0); }),
              edge(hf.x0, hf.dx, hf.nx, [&](int i) { return (sample(i, 0) - sample(i, in_y)) / hf.dy; })};
    north_ = {
        edge(hf.x0, hf.dx, hf.nx, [&](int i) { return sample(i, hf.ny - 1); }),
        edge(hf.x0, hf.dx, hf.nx, [&](int i) { return (sample(i, hf.ny - 1) - sample(i, hf.ny - 1 - in_y)) / hf.dy; })};
    west_ = {edge(hf.y0, hf.dy, hf.ny, [&](int j) { return sample(0, j); }),
             edge(hf.y0, hf.dy, hf.ny, [&](int j) { return (sample(0, j) - sample(in_x, j)) / hf.dx; })};
    east_ = {
        edge(hf.y0, hf.dy, hf.ny, [&](int j) { return sample(hf.nx - 1, j); }),
        edge(hf.y0, hf.dy, hf.ny, [&](int j) { return (sample(hf.nx - 1, j) - sample(hf.nx - 1 - in_x, j)) / hf.dx; })};
    std::vector<double> border = south_.z.z;
    for (const Side* side : {&north_, &west_, &east_})
        border.insert(border.end(), side->z.z.begin(), side->z.z.end());
    std::nth_element(border.begin(), border.begin() + border.size() / 2, border.end());
    base_ = border[border.size() / 2];
    // On a coast the sea continues to the horizon: the surround eases down to below the sea and
    // is raised to its surface, so that the edge's land slopes into the sea and ends in a coast.
    drop_to_ = base_;
    if (sea_) {
        base_ = *sea_;
        drop_to_ = *sea_ - 0.1 * (z_max_ - *sea_);
    }
    const double longer = std::max((hf.nx - 1) * hf.dx, (hf.ny - 1) * hf.dy);
    ease_ = std::max(0.25 * longer, 2.0 * std::max(hf.dx, hf.dy));
    slope_reach_ = std::min(ease_, 4.0 * std::max(hf.dx, hf.dy));
}

double Ground::Edge::primitive(double s) const
{
    const int n = int(z.size());
    const double u = std::clamp((s - start) / step, 0.0, double(n - 1));
    const int k = std::min(int(u), n - 2);
    const double f = u - k;
    return integral[k] + step * (f * z[k] + 0.5 * f * f * (z[k + 1] - z[k]));
}

double Ground::Edge::mean(double a, double b) const
{
    const int n = int(z.size());
    if (n < 2)
        return n == 1 ? z[0] : 0.0;
    const double end = start + (n - 1) * step;
    a = std::clamp(a, start, end);
    b = std::clamp(b, start, end);
    if (b - a > 1e-9 * step)
        return (primitive(b) - primitive(a)) / (b - a);
    const double u = std::clamp((a - start) / step, 0.0, double(n - 1));
    const int k = std::min(int(u), n - 2);
    return z[k] + (u - k) * (z[k + 1] - z[k]);
}

double Ground::sample_height(double x, double y) const
{
    return clamped_grid_height(hf_, x, y, [&](int i, int j) { return sample(i, j); });
}

double Ground::distance_outside(double x, double y) const
{
    const double ox = std::max({hf_.x0 - x, 0.0, x - hf_.x_max()});
    const double oy = std::max({hf_.y0 - y, 0.0, y - hf_.y_max()});
    return std::hypot(ox, oy);
}

double Ground::height(double x, double y) const
{
    if (std::isnan(x) || std::isnan(y))
        return surround_ ? base_ : z_min_;
    if (!surround_)
        return sample_height(x, y);
    const double ox = std::max(hf_.x0 - x, x - hf_.x_max()), oy = std::max(hf_.y0 - y, y - hf_.y_max());
    if (ox <= 0.0 && oy <= 0.0)
        return sample_height(x, y);
    const double d = std::hypot(std::max(ox, 0.0), std::max(oy, 0.0));
    if (!std::isfinite(d))
        return base_;
    // The nearest edge point's coordinate along each edge, and the mean of that edge within d.
    const double cx = std::clamp(x, hf_.x0, hf_.x_max()), cy = std::clamp(y, hf_.y0, hf_.y_max());
    const Side& across_x = y < hf_.y0 ? south_ : north_;  // the edge running along x
    const Side& across_y = x < hf_.x0 ? west_ : east_;    // the edge running along y
    double edge, slope;
    if (oy <= 0.0) {
        edge = across_y.z.mean(cy - d, cy + d);
        slope = across_y.slope.mean(cy - d, cy + d);
    } else if (ox <= 0.0) {
        edge = across_x.z.mean(cx - d, cx + d);
        slope = across_x.slope.mean(cx - d, cx + d);
    } else {  // a corner: from the edge along y (towards x) to the edge along x (towards y)
        const double w = std::atan2(oy, ox) / (0.5 * std::numbers::pi);
        edge = (1.0 - w) * across_y.z.mean(cy - d, cy + d) + w * across_x.z.mean(cx - d, cx + d);
        slope = (1.0 - w) * across_y.slope.mean(cy - d, cy + d) + w * across_x.slope.mean(cx - d, cx + d);
    }
    const double fade = std::max(0.0, 1.0 - d / slope_reach_);
    edge += slope * d * fade * fade;
    const double z = edge + (drop_to_ - edge) * ease_in_out(d / ease_);
    return sea_ ? std::max(z, *sea_) : z;
}

glm::dvec3 Ground::normal(double x, double y) const
{
    if (hf_.nx < 2 || hf_.ny < 2 || !std::isfinite(x) || !std::isfinite(y))
        return {0.0, 0.0, 1.0};
    if (!surround_ || inside(x, y)) {
        const double fx = std::clamp((x - hf_.x0) / hf_.dx, 0.0, double(hf_.nx - 1));
        const double fy = std::clamp((y - hf_.y0) / hf_.dy, 0.0, double(hf_.ny - 1));
        const int i = std::min(int(fx), hf_.nx - 2), j = std::min(int(fy), hf_.ny - 2);
        const double s = fx - i, r = fy - j;
        const double z00 = sample(i, j), z11 = sample(i + 1, j + 1);
        double zx, zy;
        if (s >= r) {
            zx = (sample(i + 1, j) - z00) / hf_.dx;
            zy = (z11 - sample(i + 1, j)) / hf_.dy;
        } else {
            zy = (sample(i, j + 1) - z00) / hf_.dy;
            zx = (z11 - sample(i, j + 1)) / hf_.dx;
        }
        return glm::normalize(glm::dvec3(-zx, -zy, 1.0));
    }
    const double hx = 0.01 * hf_.dx, hy = 0.01 * hf_.dy;
    const double zx = (height(x + hx, y) - height(x - hx, y)) / (2.0 * hx);
    const double zy = (height(x, y + hy) - height(x, y - hy)) / (2.0 * hy);
    return glm::normalize(glm::dvec3(-zx, -zy, 1.0));
}

}  // namespace kiri::geometry
