#include "kiri/geometry/fog/fog_target.hpp"

#include <algorithm>
#include <cmath>

namespace kiri::geometry {
namespace {

// One box pass of half-width r along x (rows), in place.
void box_rows(std::vector<double>& a, std::vector<double>& tmp, int nx, int ny, int r)
{
    if (r <= 0)
        return;
    tmp.resize(nx);
    for (int j = 0; j < ny; ++j) {
        double* p = a.data() + std::size_t(j) * nx;
        double sum = 0.0;
        for (int k = 0; k <= std::min(r, nx - 1); ++k)
            sum += p[k];
        for (int k = 0; k < nx; ++k) {
            tmp[k] = sum;
            if (k + r + 1 < nx)
                sum += p[k + r + 1];
            if (k - r >= 0)
                sum -= p[k - r];
        }
        std::copy(tmp.begin(), tmp.end(), p);
    }
}

// The same along y, a whole row of running sums at a time (contiguous memory access).
void box_columns(std::vector<double>& a, std::vector<double>& out, int nx, int ny, int r)
{
    if (r <= 0)
        return;
    out.assign(a.size(), 0.0);
    std::vector<double> sum(nx, 0.0);
    auto row = [&](int j) { return a.data() + std::size_t(j) * nx; };
    for (int k = 0; k <= std::min(r, ny - 1); ++k)
        for (int i = 0; i < nx; ++i)
            sum[i] += row(k)[i];
    for (int j = 0; j < ny; ++j) {
        std::copy(sum.begin(), sum.end(), out.begin() + std::size_t(j) * nx);
        if (j + r + 1 < ny)
            for (int i = 0; i < nx; ++i)
                sum[i] += row(j + r + 1)[i];
        if (j - r >= 0)
            for (int i = 0; i < nx; ++i)
                sum[i] -= row(j - r)[i];
    }
    a.swap(out);
}

int box_radius(double sigma_cells)
{
    const double w = std::sqrt(4.0 * sigma_cells * sigma_cells + 1.0);
    return std::max(0, static_cast<int>(std::lround((w - 1.0) / 2.0)));
}

}  // namespace

Heightfield smooth_heightfield(const Heightfield& hf, double sigma)
{
    Heightfield out = hf;
    if (!(sigma > 0.0) || hf.nx < 2 || hf.ny < 2)
        return out;
    const std::size_t n = hf.size();
    std::vector<double> value(n), weight(n), tmp;
    for (std::size_t k = 0; k < n; ++k) {
        const double m = hf.valid.empty() ? 1.0 : double(hf.valid[k] != 0);
        value[k] = m * hf.z[k];
        weight[k] = m;
    }
    const int rx = box_radius(sigma / hf.dx), ry = box_radius(sigma / hf.dy);
    for (auto* a : {&value, &weight})
        for (int pass = 0; pass < 3; ++pass) {
            box_rows(*a, tmp, hf.nx, hf.ny, rx);
            box_columns(*a, tmp, hf.nx, hf.ny, ry);
        }
    for (std::size_t k = 0; k < n; ++k)
        out.z[k] = weight[k] > 1e-12 ? value[k] / weight[k] : hf.z[k];
    return out;
}

double sample_bilinear(const Heightfield& hf, double x, double y)
{
    if (hf.nx < 2 || hf.ny < 2)
        return hf.z.empty() ? 0.0 : hf.z[0];
    const double fx = std::clamp((x - hf.x0) / hf.dx, 0.0, double(hf.nx - 1));
    const double fy = std::clamp((y - hf.y0) / hf.dy, 0.0, double(hf.ny - 1));
    const int i = std::min(int(fx), hf.nx - 2), j = std::min(int(fy), hf.ny - 2);
    const double s = fx - i, t = fy - j;
    return (1 - t) * ((1 - s) * hf.at(i, j) + s * hf.at(i + 1, j)) +
        t * ((1 - s) * hf.at(i, j + 1) + s * hf.at(i + 1, j + 1));
}

bool has_data(const Heightfield& hf, double x, double y)
{
    if (hf.valid.empty())
        return true;
    if (hf.nx < 2 || hf.ny < 2)
        return hf.valid[0] != 0;
    const double fx = std::clamp((x - hf.x0) / hf.dx, 0.0, double(hf.nx - 1));
    const double fy = std::clamp((y - hf.y0) / hf.dy, 0.0, double(hf.ny - 1));
    const int i = std::min(int(fx), hf.nx - 2), j = std::min(int(fy), hf.ny - 2);
    auto ok = [&](int a, int b) { return hf.valid[std::size_t(b) * hf.nx + a] != 0; };
    return ok(i, j) && ok(i + 1, j) && ok(i, j + 1) && ok(i + 1, j + 1);
}

}  // namespace kiri::geometry
