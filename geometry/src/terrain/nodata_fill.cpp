#include "terrain/nodata_fill.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace kiri::geometry {
namespace {

// Sweeps per level stop once no cell moves by more than this share of the heights' range, or
// after max_sweeps (each level starts from the coarser solution, so few are needed).
constexpr double tolerance = 1e-10;
constexpr int max_sweeps = 400;

struct FillGrid {
    int nx = 0, ny = 0;
    std::vector<double> z;
    std::vector<std::uint8_t> valid;
};

// Sweeps the voids of g towards the discrete harmonic interpolant: each void the mean of its
// 4-neighbours inside the grid (a missing neighbour is no flux through the border).
void relax(FillGrid& g, const std::vector<std::size_t>& voids, double scale)
{
    const int nx = g.nx, ny = g.ny;
    const double stop = tolerance * scale;
    for (int sweep = 0; sweep < max_sweeps; ++sweep) {
        double largest = 0.0;
        for (const std::size_t k : voids) {
            const int i = int(k % std::size_t(nx)), j = int(k / std::size_t(nx));
            double sum = 0.0;
            int count = 0;
            if (i > 0)
                sum += g.z[k - 1], ++count;
            if (i + 1 < nx)
                sum += g.z[k + 1], ++count;
            if (j > 0)
                sum += g.z[k - std::size_t(nx)], ++count;
            if (j + 1 < ny)
                sum += g.z[k + std::size_t(nx)], ++count;
            if (count == 0)
                continue;  // a 1 x 1 grid
            // Plain Gauss-Seidel: every value stays within its neighbours' range at every sweep,
            // and a lone void in a plane takes the plane's value exactly.
            const double value = sum / count;
            largest = std::max(largest, std::abs(value - g.z[k]));
            g.z[k] = value;
        }
        if (largest <= stop)
            return;
    }
}

// Fills the voids of g (which holds at least one valid cell) coarse to fine.
void fill(FillGrid& g, double scale)
{
    std::vector<std::size_t> voids;
    for (std::size_t k = 0; k < g.z.size(); ++k)
        if (!g.valid[k])
            voids.push_back(k);
    if (voids.empty())
        return;
    // The coarser level: each cell the mean of the valid cells of its 2 x 2 block.
    FillGrid c;
    c.nx = (g.nx + 1) / 2;
    c.ny = (g.ny + 1) / 2;
    c.z.assign(std::size_t(c.nx) * c.ny, 0.0);
    c.valid.assign(c.z.size(), 0);
    std::vector<int> counts(c.z.size(), 0);
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            const std::size_t k = std::size_t(j) * g.nx + i;
            if (!g.valid[k])
                continue;
            const std::size_t ck = std::size_t(j / 2) * c.nx + i / 2;
            c.z[ck] += g.z[k];
            ++counts[ck];
        }
    for (std::size_t k = 0; k < c.z.size(); ++k)
        if (counts[k] > 0) {
            c.z[k] /= counts[k];
            c.valid[k] = 1;
        }
    if (c.z.size() < g.z.size())
        fill(c, scale);
    else  // 1 x 1 cannot shrink, and holds a valid cell
        std::fill(c.z.begin(), c.z.end(), c.z[0]);
    // Each void starts from the coarser membrane, bilinear at its centre, then is relaxed.
    for (const std::size_t k : voids) {
        const int i = int(k % std::size_t(g.nx)), j = int(k / std::size_t(g.nx));
        const double u = std::clamp((i - 0.5) / 2.0, 0.0, double(c.nx - 1));
        const double v = std::clamp((j - 0.5) / 2.0, 0.0, double(c.ny - 1));
        const int i0 = std::min(int(u), std::max(c.nx - 2, 0)), j0 = std::min(int(v), std::max(c.ny - 2, 0));
        const int i1 = std::min(i0 + 1, c.nx - 1), j1 = std::min(j0 + 1, c.ny - 1);
        const double s = u - i0, t = v - j0;
        const auto at = [&](int a, int b) { return c.z[std::size_t(b) * c.nx + a]; };
        g.z[k] = (1 - t) * ((1 - s) * at(i0, j0) + s * at(i1, j0)) + t * ((1 - s) * at(i0, j1) + s * at(i1, j1));
    }
    relax(g, voids, scale);
}

}  // namespace

void fill_voids_smoothly(int nx, int ny, std::vector<double>& z, const std::vector<std::uint8_t>& valid)
{
    double lo = INFINITY, hi = -INFINITY;
    for (std::size_t k = 0; k < z.size(); ++k)
        if (valid[k]) {
            lo = std::min(lo, z[k]);
            hi = std::max(hi, z[k]);
        }
    if (!(lo <= hi))
        return;  // no valid cell: the caller refuses such a grid
    FillGrid g{nx, ny, std::move(z), valid};
    fill(g, std::max(hi - lo, 1.0));
    z = std::move(g.z);
}

}  // namespace kiri::geometry
