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
    int s = 1;
    const double cell = std::min(hf.dx, hf.dy);
    if (options.grid_spacing > cell)
        s = int(std::ceil(options.grid_spacing / cell - 1e-9));
    while ((hf.nx - 1) / s + 1 > options.max_grid_side || (hf.ny - 1) / s + 1 > options.max_grid_side)
        ++s;
    // A grid only a few cells wide keeps its two edges on its short side, whatever the stride
    // its long side needs.
    const int sx = std::max(1, std::min(s, hf.nx - 1)), sy = std::max(1, std::min(s, hf.ny - 1));
    MediumGrid g;
    g.nx = (hf.nx - 1) / sx + 1;
    g.ny = (hf.ny - 1) / sy + 1;
    g.x0 = hf.x0;
    g.y0 = hf.y0;
    g.dx = hf.dx * sx;
    g.dy = hf.dy * sy;
    const std::size_t n = std::size_t(g.nx) * g.ny;
    g.floor.resize(n);
    g.bottom.resize(n);
    g.top.resize(n);
    g.coverage.resize(n);
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            const std::size_t k = std::size_t(j * sy) * hf.nx + std::size_t(i * sx), q = std::size_t(j) * g.nx + i;
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
