#include "kiri/geometry/medium/light_volume.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace kiri::geometry {

namespace {

// K_l^m sqrt(2) (m > 0) or K_l^0 of the real harmonics, K_l^m = sqrt((2l + 1) / (4 pi) (l - m)! / (l + m)!).
struct HarmonicNorms {
    std::array<std::array<double, light_volume_max_bands>, light_volume_max_bands> k{};
    HarmonicNorms()
    {
        for (int l = 0; l < light_volume_max_bands; ++l)
            for (int m = 0; m <= l; ++m) {
                double ratio = 1.0;  // (l - m)! / (l + m)!
                for (int q = l - m + 1; q <= l + m; ++q)
                    ratio /= q;
                k[l][m] =
                    std::sqrt((2.0 * l + 1.0) / (4.0 * std::numbers::pi) * ratio) * (m > 0 ? std::numbers::sqrt2 : 1.0);
            }
    }
};

}  // namespace

void real_spherical_harmonics(const glm::dvec3& d, int bands, double* out)
{
    static const HarmonicNorms norms;
    const int n = std::clamp(bands, 1, light_volume_max_bands);
    const double len = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    const glm::dvec3 u = len > 0.0 && std::isfinite(len) ? d / len : glm::dvec3(0.0, 0.0, 1.0);
    const double x = std::clamp(u.z, -1.0, 1.0);
    // Associated Legendre functions without the Condon-Shortley phase and without their factor
    // sin^m(theta), by the standard recurrences; that factor joins the azimuth's:
    // sin^m(theta) (cos(m phi), sin(m phi)) = (Re, Im) (u.x + i u.y)^m, no trigonometry.
    std::array<std::array<double, light_volume_max_bands>, light_volume_max_bands> p{};
    double pmm = 1.0;
    for (int m = 0; m < n; ++m) {
        if (m > 0)
            pmm *= 2.0 * m - 1.0;
        p[m][m] = pmm;
        if (m + 1 < n)
            p[m + 1][m] = x * (2.0 * m + 1.0) * pmm;
        for (int l = m + 2; l < n; ++l)
            p[l][m] = ((2.0 * l - 1.0) * x * p[l - 1][m] - (l + m - 1.0) * p[l - 2][m]) / (l - m);
    }
    double re = 1.0, im = 0.0;  // (u.x + i u.y)^m
    for (int m = 0; m < n; ++m) {
        for (int l = m; l < n; ++l) {
            const double a = norms.k[l][m] * p[l][m];
            if (m == 0) {
                out[l * (l + 1)] = a;
            } else {
                out[l * (l + 1) + m] = a * re;
                out[l * (l + 1) - m] = a * im;
            }
        }
        const double r = re * u.x - im * u.y;
        im = re * u.y + im * u.x;
        re = r;
    }
}

double shell_height(const MediumColumn& column, double z)
{
    const double thick = column.top - column.floor;
    if (!(thick > 0.0) || !std::isfinite(thick) || !(z >= column.floor) || !(z <= column.top))
        return -1.0;
    return std::clamp((z - column.floor) / thick, 0.0, 1.0);
}

namespace {

// Bilinear between the samples of a grid of gnx x gny spanning the cells' rectangle
// [x0, x0 + nx dx] x [y0, y0 + ny dy] (the floors' and the shadow's tops); `none` without one.
double rectangle_grid_at(const LightVolume& v, const std::vector<double>& samples, int gnx, int gny, double x, double y,
                         double none)
{
    if (gnx < 2 || gny < 2 || samples.size() != std::size_t(gnx) * gny || !std::isfinite(x) || !std::isfinite(y))
        return none;
    const auto axis = [](double t, int n, int& i0, double& f) {
        const double g = std::clamp(t * (n - 1), 0.0, double(n - 1));
        i0 = std::min(int(g), n - 2);
        f = g - i0;
    };
    int i, j;
    double fx, fy;
    axis((x - v.x0) / (v.nx * v.dx), gnx, i, fx);
    axis((y - v.y0) / (v.ny * v.dy), gny, j, fy);
    const double* f = &samples[std::size_t(j) * gnx + i];
    return (1.0 - fy) * ((1.0 - fx) * f[0] + fx * f[1]) + fy * ((1.0 - fx) * f[gnx] + fx * f[gnx + 1]);
}

}  // namespace

double LightVolume::floor_at(double x, double y) const
{
    return rectangle_grid_at(*this, floors, floor_nx, floor_ny, x, y, std::numeric_limits<double>::infinity());
}

double LightVolume::shadow_top_at(double x, double y) const
{
    return rectangle_grid_at(*this, shadow_tops, shadow_nx, shadow_ny, x, y, -std::numeric_limits<double>::infinity());
}

bool LightVolume::has_shadow_parts() const
{
    return !empty() && shadow_nx >= 2 && shadow_ny >= 2 && shadow_tops.size() == std::size_t(shadow_nx) * shadow_ny &&
        class_means.size() == std::size_t(nx) * ny * nz * 2;
}

MediumColumn LightVolume::shell(MediumColumn c, double x, double y) const
{
    if (!(haze_extinction > 0.0))
        return c;
    c.floor = std::min(c.floor, floor_at(x, y));
    if (haze_top > c.floor && haze_top > c.top)
        c.top = haze_top;
    return c;
}

double LightVolume::column_scale(const MediumColumn& column) const
{
    if (!(column_extinction > 0.0) || !std::isfinite(column_extinction))
        return 1.0;
    double tau = column_extinction * std::clamp(column.coverage, 0.0, 1.0) * std::max(column.top - column.floor, 0.0);
    if (haze_extinction > 0.0 && haze_top > column.floor && haze_scale_height > 0.0) {
        // The height fog's optical depth from the floor up to its top: constant under its base,
        // exponential above (HeightFog::optical_depth along a vertical, in closed form).
        const double above = std::max(column.floor, haze_base);
        tau += haze_extinction * std::max(std::min(haze_top, haze_base) - column.floor, 0.0) +
            haze_extinction * haze_scale_height *
                (std::exp(-(above - haze_base) / haze_scale_height) -
                 std::exp(-(haze_top - haze_base) / haze_scale_height));
    }
    return std::isfinite(tau) ? std::max(-std::expm1(-std::max(tau, 0.0)), 1e-6) : 1.0;
}

namespace {

// The eight cells around (x, y, h) and their trilinear weights, between cell centres (at i + 1/2:
// the texel convention of a GPU's linear filtering), clamped to the outer ones.
struct CellCorners {
    std::array<std::size_t, 8> cell{};
    double fx = 0.0, fy = 0.0, fz = 0.0;
    // Corner q's weight times `scale`, multiplied in the one order every caller uses.
    double weight(std::size_t q, double scale = 1.0) const
    {
        return scale * (q & 1 ? fx : 1.0 - fx) * (q & 2 ? fy : 1.0 - fy) * (q & 4 ? fz : 1.0 - fz);
    }
};

CellCorners corners_at(const LightVolume& v, double x, double y, double h)
{
    const auto axis = [](double t, int n, int& i0, int& i1, double& f) {
        const double g = std::clamp(t - 0.5, 0.0, double(n - 1));
        i0 = std::min(int(g), n - 1);
        i1 = std::min(i0 + 1, n - 1);
        f = g - i0;
    };
    int i0, i1, j0, j1, k0, k1;
    double fx, fy, fz;
    axis((x - v.x0) / v.dx, v.nx, i0, i1, fx);
    axis((y - v.y0) / v.dy, v.ny, j0, j1, fy);
    axis(std::clamp(h, 0.0, 1.0) * v.nz, v.nz, k0, k1, fz);
    CellCorners c;
    for (int q = 0; q < 8; ++q) {
        const int i = q & 1 ? i1 : i0, j = q & 2 ? j1 : j0, k = q & 4 ? k1 : k0;
        c.cell[std::size_t(q)] = (std::size_t(k) * v.ny + j) * v.nx + i;
    }
    c.fx = fx;
    c.fy = fy;
    c.fz = fz;
    return c;
}

}  // namespace

void LightVolume::moments_at(double x, double y, double h, double* out, double scale) const
{
    const int nc = std::max(bands, 0) * std::max(bands, 0);
    std::fill(out, out + nc, 0.0);
    if (empty() || !std::isfinite(x) || !std::isfinite(y) || !std::isfinite(h) || !(scale >= 0.0) ||
        !std::isfinite(scale) || moments.size() != std::size_t(nx) * ny * nz * nc)
        return;
    const CellCorners c = corners_at(*this, x, y, h);
    for (std::size_t q = 0; q < 8; ++q) {
        const double w = c.weight(q, scale);
        if (w == 0.0)
            continue;
        const double* m = &moments[c.cell[q] * nc];
        for (int k = 0; k < nc; ++k)
            out[k] += w * m[k];
    }
}

void LightVolume::phase_weights(const glm::dvec3& towards, double g, double* out) const
{
    const int n = std::clamp(bands, 1, light_volume_max_bands);
    real_spherical_harmonics(towards, n, out);
    const double lobe = std::isfinite(g) ? std::clamp(g, -0.999, 0.999) : 0.0;
    double gl = 1.0;
    for (int l = 0; l < n; ++l, gl *= lobe)
        for (int q = l * l; q < (l + 1) * (l + 1); ++q)
            out[q] *= gl;
}

double LightVolume::in_scattered(double x, double y, double h, const double* weights, double scale) const
{
    if (empty())
        return 0.0;
    std::array<double, light_volume_max_bands * light_volume_max_bands> m{};
    moments_at(x, y, h, m.data(), scale);
    double sum = 0.0;
    for (int q = 0; q < bands * bands; ++q)
        sum += weights[q] * m[q];
    return std::isfinite(sum) ? std::max(sum, 0.0) : 0.0;
}

double LightVolume::in_scattered_at(double x, double y, double z, double h, const double* weights, double scale) const
{
    if (!has_shadow_parts() || !std::isfinite(z))
        return in_scattered(x, y, h, weights, scale);
    std::array<double, light_volume_max_bands * light_volume_max_bands> m{};
    moments_at(x, y, h, m.data(), scale);
    double sum = 0.0;
    for (int q = 0; q < bands * bands; ++q)
        sum += weights[q] * m[q];
    if (m[0] > 0.0) {
        const std::size_t part = z < shadow_top_at(x, y) ? 1 : 0;
        const CellCorners c = corners_at(*this, x, y, h);
        double mean = 0.0;
        for (std::size_t q = 0; q < 8; ++q)
            mean += c.weight(q, scale) * class_means[c.cell[q] * 2 + part];
        sum *= std::clamp(mean / m[0], 0.0, 64.0);
    }
    return std::isfinite(sum) ? std::max(sum, 0.0) : 0.0;
}

double LightVolume::in_scattered(double x, double y, double h, const glm::dvec3& towards, double g, double scale) const
{
    if (empty())
        return 0.0;
    std::array<double, light_volume_max_bands * light_volume_max_bands> w{};
    phase_weights(towards, g, w.data());
    return in_scattered(x, y, h, w.data(), scale);
}

}  // namespace kiri::geometry
