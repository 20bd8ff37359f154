#include "kiri/geometry/medium/light_volume.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace kiri::geometry {

void real_spherical_harmonics(const glm::dvec3& d, int bands, double* out)
{
    const int n = std::clamp(bands, 1, light_volume_max_bands);
    const double len = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    const glm::dvec3 u = len > 0.0 && std::isfinite(len) ? d / len : glm::dvec3(0.0, 0.0, 1.0);
    const double x = std::clamp(u.z, -1.0, 1.0), s = std::sqrt(std::max(0.0, 1.0 - x * x));
    const double phi = std::atan2(u.y, u.x);
    // Associated Legendre functions P_l^m(x) (without the Condon-Shortley phase) by the
    // standard recurrences, then Y_lm = K_l^m P_l^m(x) times sqrt(2) cos(m phi) or sin(|m| phi).
    std::array<std::array<double, light_volume_max_bands>, light_volume_max_bands> p{};
    double pmm = 1.0;
    for (int m = 0; m < n; ++m) {
        if (m > 0)
            pmm *= (2.0 * m - 1.0) * s;
        p[m][m] = pmm;
        if (m + 1 < n)
            p[m + 1][m] = x * (2.0 * m + 1.0) * pmm;
        for (int l = m + 2; l < n; ++l)
            p[l][m] = ((2.0 * l - 1.0) * x * p[l - 1][m] - (l + m - 1.0) * p[l - 2][m]) / (l - m);
    }
    for (int l = 0; l < n; ++l)
        for (int m = 0; m <= l; ++m) {
            double ratio = 1.0;  // (l - m)! / (l + m)!
            for (int k = l - m + 1; k <= l + m; ++k)
                ratio /= k;
            const double k_lm = std::sqrt((2.0 * l + 1.0) / (4.0 * std::numbers::pi) * ratio);
            if (m == 0) {
                out[l * (l + 1)] = k_lm * p[l][0];
            } else {
                out[l * (l + 1) + m] = std::numbers::sqrt2 * k_lm * std::cos(m * phi) * p[l][m];
                out[l * (l + 1) - m] = std::numbers::sqrt2 * k_lm * std::sin(m * phi) * p[l][m];
            }
        }
}

double shell_height(const MediumColumn& column, double z)
{
    const double thick = column.top - column.floor;
    if (!(thick > 0.0) || !std::isfinite(thick) || !(z >= column.floor) || !(z <= column.top))
        return -1.0;
    return std::clamp((z - column.floor) / thick, 0.0, 1.0);
}

void LightVolume::moments_at(double x, double y, double h, double* out) const
{
    const int nc = std::max(bands, 0) * std::max(bands, 0);
    std::fill(out, out + nc, 0.0);
    if (empty() || !std::isfinite(x) || !std::isfinite(y) || !std::isfinite(h) ||
        moments.size() != std::size_t(nx) * ny * nz * nc)
        return;
    // Cell centres at i + 1/2: the texel convention of a GPU's linear filtering, clamped to the edge.
    const auto axis = [](double v, int n, int& i0, int& i1, double& f) {
        const double g = std::clamp(v - 0.5, 0.0, double(n - 1));
        i0 = std::min(int(g), n - 1);
        i1 = std::min(i0 + 1, n - 1);
        f = g - i0;
    };
    int i0, i1, j0, j1, k0, k1;
    double fx, fy, fz;
    axis((x - x0) / dx, nx, i0, i1, fx);
    axis((y - y0) / dy, ny, j0, j1, fy);
    axis(std::clamp(h, 0.0, 1.0) * nz, nz, k0, k1, fz);
    for (int c = 0; c < 8; ++c) {
        const int i = c & 1 ? i1 : i0, j = c & 2 ? j1 : j0, k = c & 4 ? k1 : k0;
        const double w = (c & 1 ? fx : 1.0 - fx) * (c & 2 ? fy : 1.0 - fy) * (c & 4 ? fz : 1.0 - fz);
        if (w == 0.0)
            continue;
        const double* m = &moments[((std::size_t(k) * ny + j) * nx + i) * nc];
        for (int q = 0; q < nc; ++q)
            out[q] += w * m[q];
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

double LightVolume::in_scattered(double x, double y, double h, const double* weights) const
{
    if (empty())
        return 0.0;
    std::array<double, light_volume_max_bands * light_volume_max_bands> m{};
    moments_at(x, y, h, m.data());
    double sum = 0.0;
    for (int q = 0; q < bands * bands; ++q)
        sum += weights[q] * m[q];
    return std::isfinite(sum) ? std::max(sum, 0.0) : 0.0;
}

double LightVolume::in_scattered(double x, double y, double h, const glm::dvec3& towards, double g) const
{
    if (empty())
        return 0.0;
    std::array<double, light_volume_max_bands * light_volume_max_bands> w{};
    phase_weights(towards, g, w.data());
    return in_scattered(x, y, h, w.data());
}

}  // namespace kiri::geometry
