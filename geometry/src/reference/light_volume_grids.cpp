#include "reference/light_volume_grids.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/vec2.hpp>

#include "core/parallel_rows.hpp"
#include "kiri/geometry/fog/fog_target.hpp"

namespace kiri::geometry {
namespace {

// Samples a cell of the grids over the cells' rectangle (the floors, the terrain's shadow's tops):
// two a DEM spacing, so that the shadow of a ridge and the ground of a valley are resolved as the
// DEM resolves them, at least four and at most sixteen a cell.
int samples_per_cell(const LightVolume& v, const Heightfield& hf)
{
    const double spacing = std::max(std::min(hf.dx, hf.dy), 1e-9);
    const double wanted = 2.0 * std::max(v.dx, v.dy) / spacing;
    return std::clamp(int(std::ceil(std::isfinite(wanted) ? wanted : 16.0)), 4, 16);
}

}  // namespace

namespace detail {

// The cells' floors where the height fog lies under the Medium's floor (LightVolume::floors):
// samples_per_cell a cell, each the lower of the Medium's floor there and the lowest of the DEM's
// samples within a floor sample's spacing of it (the ground between samples is no lower: its
// triangles span them), where that ground is under the height fog's top.
void lower_floors_to_the_ground(LightVolume& v, const Medium& medium, const Heightfield& hf)
{
    const int per_cell = samples_per_cell(v, hf);
    v.floor_nx = per_cell * v.nx + 1;
    v.floor_ny = per_cell * v.ny + 1;
    v.floors.assign(std::size_t(v.floor_nx) * v.floor_ny, 0.0);
    const double sx = v.nx * v.dx / (v.floor_nx - 1), sy = v.ny * v.dy / (v.floor_ny - 1);
    bool lowered = false;
    for (int b = 0; b < v.floor_ny; ++b)
        for (int a = 0; a < v.floor_nx; ++a) {
            const double x = v.x0 + a * sx, y = v.y0 + b * sy;
            double floor = medium.column(x, y).floor;
            const int i0 = std::clamp(int(std::floor((x - sx - hf.x0) / hf.dx)), 0, hf.nx - 1),
                      i1 = std::clamp(int(std::ceil((x + sx - hf.x0) / hf.dx)), 0, hf.nx - 1),
                      j0 = std::clamp(int(std::floor((y - sy - hf.y0) / hf.dy)), 0, hf.ny - 1),
                      j1 = std::clamp(int(std::ceil((y + sy - hf.y0) / hf.dy)), 0, hf.ny - 1);
            double ground = std::numeric_limits<double>::infinity();
            for (int j = j0; j <= j1; ++j)
                for (int i = i0; i <= i1; ++i)
                    ground = std::min(ground, hf.at(i, j));
            if (ground < v.haze_top && ground < floor) {
                floor = ground;
                lowered = true;
            }
            v.floors[std::size_t(b) * v.floor_nx + a] = floor;
        }
    if (!lowered) {  // the Medium's floor everywhere: no grid needed
        v.floor_nx = v.floor_ny = 0;
        v.floors.clear();
    }
}

// The terrain's shadow's top on the cells' rectangle (LightVolume::shadow_tops), samples_per_cell
// a cell: at each, the highest of the ground there and, along the horizontal line towards the sun,
// of the ground at each point less its distance times tan(elevation) (how far the sunlight grazing
// that point has sunk on its way here), until no ground is high enough to matter. The points are
// where the line crosses the DEM's rows and columns of samples, on which its triangles' edges lie
// (a ridge one sample wide is seen at its crest, where even steps of half a spacing straddle it).
void mark_the_terrains_shadow(LightVolume& v, const Heightfield& hf, const glm::dvec3& sun, int threads)
{
    const int per_cell = samples_per_cell(v, hf);
    if (hf.nx < 2 || hf.ny < 2 || hf.z.empty())
        return;
    v.shadow_nx = per_cell * v.nx + 1;
    v.shadow_ny = per_cell * v.ny + 1;
    v.shadow_tops.assign(std::size_t(v.shadow_nx) * v.shadow_ny, 0.0);
    const double sx = v.nx * v.dx / (v.shadow_nx - 1), sy = v.ny * v.dy / (v.shadow_ny - 1);
    const double across = std::hypot(sun.x, sun.y);
    const double sink = across > 0.0 ? sun.z / across : std::numeric_limits<double>::infinity();  // tan(elevation)
    const glm::dvec2 towards = across > 0.0 ? glm::dvec2(sun.x, sun.y) / across : glm::dvec2(0.0);
    const double highest = *std::max_element(hf.z.begin(), hf.z.end());
    const double xmin = hf.x0, xmax = hf.x_max(), ymin = hf.y0, ymax = hf.y_max();
    // The line's crossings of the sample lines of one axis: o + towards t at t = first + k gap.
    const auto crossings = [&](double o, double u, double x0, double spacing, double& first, double& gap) {
        if (std::abs(u) < 1e-12)
            return false;
        const double g = (o - x0) / spacing;
        const double next = u > 0.0 ? std::floor(g) + 1.0 : std::ceil(g) - 1.0;
        first = (x0 + next * spacing - o) / u;
        gap = spacing / std::abs(u);
        return true;
    };
    detail::for_rows_in_parallel(threads, v.shadow_ny, [&](auto next_row) {
        for (int b = next_row(); b < v.shadow_ny; b = next_row())
            for (int a = 0; a < v.shadow_nx; ++a) {
                const double x = v.x0 + a * sx, y = v.y0 + b * sy;
                double top = sample_bilinear(hf, x, y);
                if (std::isfinite(sink))
                    for (int axis = 0; axis < 2; ++axis) {
                        double t = 0.0, gap = 0.0;
                        if (!(axis == 0 ? crossings(x, towards.x, hf.x0, hf.dx, t, gap)
                                        : crossings(y, towards.y, hf.y0, hf.dy, t, gap)))
                            continue;
                        for (; highest - t * sink > top; t += gap) {
                            const double qx = x + towards.x * t, qy = y + towards.y * t;
                            if (qx < xmin - 1e-9 || qx > xmax + 1e-9 || qy < ymin - 1e-9 || qy > ymax + 1e-9)
                                break;
                            top = std::max(top, sample_bilinear(hf, qx, qy) - t * sink);
                        }
                    }
                v.shadow_tops[std::size_t(b) * v.shadow_nx + a] = top;
            }
    });
}

// Fills the parts too small to measure (`known` 0) with the mean of their known neighbours' (the
// 26 around, repeated outwards), else the cell's own L_00.
void fill_unknown_parts(LightVolume& v, std::vector<std::uint8_t>& known)
{
    const std::size_t cells = std::size_t(v.nx) * v.ny * v.nz;
    for (int pass = 0; pass < 64; ++pass) {
        std::vector<std::uint8_t> next = known;
        bool changed = false, missing = false;
        for (std::size_t c = 0; c < cells; ++c) {
            const int i = int(c % std::size_t(v.nx)), j = int(c / std::size_t(v.nx) % std::size_t(v.ny)),
                      k = int(c / (std::size_t(v.nx) * v.ny));
            for (int part = 0; part < 2; ++part) {
                if (known[c * 2 + std::size_t(part)])
                    continue;
                double sum = 0.0;
                int n = 0;
                for (int dk = -1; dk <= 1; ++dk)
                    for (int dj = -1; dj <= 1; ++dj)
                        for (int di = -1; di <= 1; ++di) {
                            const int ii = i + di, jj = j + dj, kk = k + dk;
                            if (ii < 0 || jj < 0 || kk < 0 || ii >= v.nx || jj >= v.ny || kk >= v.nz)
                                continue;
                            const std::size_t d = (std::size_t(kk) * v.ny + jj) * v.nx + ii;
                            if (known[d * 2 + std::size_t(part)]) {
                                sum += v.class_means[d * 2 + std::size_t(part)];
                                ++n;
                            }
                        }
                if (n > 0) {
                    v.class_means[c * 2 + std::size_t(part)] = sum / n;
                    next[c * 2 + std::size_t(part)] = 1;
                    changed = true;
                } else {
                    missing = true;
                }
            }
        }
        known = std::move(next);
        if (!changed || !missing)
            break;
    }
    const int nc = v.bands * v.bands;
    for (std::size_t c = 0; c < cells; ++c)
        for (std::size_t part = 0; part < 2; ++part)
            if (!known[c * 2 + part])
                v.class_means[c * 2 + part] = v.moments[c * std::size_t(nc)];
}

}  // namespace detail
}  // namespace kiri::geometry
