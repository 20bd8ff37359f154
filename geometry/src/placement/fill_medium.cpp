#include "kiri/geometry/placement/fill_medium.hpp"

#include <algorithm>
#include <cmath>

#include "kiri/geometry/core/error.hpp"

namespace kiri::geometry {

Medium fill_medium(const Terrain& terrain, const PlacedFog& placed, const MediumOptions& options,
                   const MediumDetail& detail, const std::string& label)
{
    validate_medium_options(options, label);
    const Heightfield& hf = terrain.heightfield();
    const FogColumns& c = placed.columns;
    if (c.nx != hf.nx || c.ny != hf.ny || placed.medium_bottom.size() != hf.size())
        throw InputError(label, "/fog", "the placed fog is not on the terrain's grid");
    // The grid spans the fog's bounds (its columns' bounding box in samples), not the whole
    // terrain: a fog in a corner of a large DEM keeps its grid (and the memory, and the volume
    // renderers' boxes) to the corner, with one sample of uncovered margin on each side so that
    // the coverage falls to 0 inside the grid as it did over the whole terrain.
    int lo_i = hf.nx, hi_i = -1, lo_j = hf.ny, hi_j = -1;
    for (int j = 0; j < hf.ny; ++j)
        for (int i = 0; i < hf.nx; ++i)
            if (c.mask[std::size_t(j) * hf.nx + i]) {
                lo_i = std::min(lo_i, i), hi_i = std::max(hi_i, i);
                lo_j = std::min(lo_j, j), hi_j = std::max(hi_j, j);
            }
    if (hi_i < 0) {  // no fog: the whole terrain, flat on the ground
        lo_i = lo_j = 0;
        hi_i = hf.nx - 1;
        hi_j = hf.ny - 1;
    }
    int s = 1;
    const double cell = std::min(hf.dx, hf.dy);
    if (options.grid_spacing > cell)
        s = int(std::ceil(options.grid_spacing / cell - 1e-9));
    // Samples on the terrain's multiples of the stride (those the whole-terrain grid had), from
    // one stride before the fog to one after it, inside the terrain.
    const auto first = [](int lo, int stride) { return std::max(0, (lo / stride - 1) * stride); };
    const auto last = [](int hi, int n, int stride) {
        return std::min((n - 1) / stride * stride, (hi / stride + 2) * stride);
    };
    const auto side = [&](int lo, int hi, int n, int stride) {
        return (last(hi, n, stride) - first(lo, stride)) / stride + 1;
    };
    // The memory budget: a side of at most max_grid_side samples over the fog's bounds.
    while (side(lo_i, hi_i, hf.nx, s) > options.max_grid_side || side(lo_j, hi_j, hf.ny, s) > options.max_grid_side)
        ++s;
    // A grid only a few cells wide keeps its two edges on its short side, whatever the stride
    // its long side needs.
    const int sx = std::max(1, std::min(s, hf.nx - 1)), sy = std::max(1, std::min(s, hf.ny - 1));
    const int i0 = first(lo_i, sx), j0 = first(lo_j, sy);
    const int i1 = last(hi_i, hf.nx, sx), j1 = last(hi_j, hf.ny, sy);
    MediumGrid g;
    g.nx = (i1 - i0) / sx + 1;
    g.ny = (j1 - j0) / sy + 1;
    g.x0 = hf.x_of(i0);
    g.y0 = hf.y_of(j0);
    g.dx = hf.dx * sx;
    g.dy = hf.dy * sy;
    const std::size_t n = std::size_t(g.nx) * g.ny;
    g.floor.resize(n);
    g.bottom.resize(n);
    g.top.resize(n);
    g.coverage.resize(n);
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            const std::size_t k = std::size_t(j0 + j * sy) * hf.nx + std::size_t(i0 + i * sx),
                              q = std::size_t(j) * g.nx + i;
            const double ground = hf.z[k];
            if (!c.mask[k]) {
                g.floor[q] = g.bottom[q] = g.top[q] = ground;
                g.coverage[q] = 0.0;
                continue;
            }
            g.top[q] = c.top[k];
            g.bottom[q] = std::min(placed.medium_bottom[k], c.top[k]);
            g.floor[q] = std::clamp(std::max(c.bottom[k], ground), g.bottom[q], c.top[k]);
            g.coverage[q] = 1.0;
        }
    return Medium(std::move(g), options, detail);
}

}  // namespace kiri::geometry
