#include "kiri/geometry/layers/layer_medium.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "kiri/geometry/core/error.hpp"

namespace kiri::geometry {
namespace {

// The atlas alpha at atlas coordinates uv, filtered as GL_LINEAR + GL_CLAMP_TO_EDGE does.
double atlas_alpha(const LayerTexture& t, const glm::dvec2& uv)
{
    if (t.width < 1 || t.height < 1)
        return 1.0;
    const double x = std::clamp(uv.x * t.width - 0.5, 0.0, double(t.width - 1));
    const double y = std::clamp(uv.y * t.height - 0.5, 0.0, double(t.height - 1));
    const int i = std::min(int(x), t.width - 1), j = std::min(int(y), t.height - 1);
    const int i1 = std::min(i + 1, t.width - 1), j1 = std::min(j + 1, t.height - 1);
    const double fx = x - i, fy = y - j;
    auto a = [&](int ii, int jj) { return t.rgba[(std::size_t(jj) * t.width + ii) * 4 + 3] / 255.0; };
    const double lo = a(i, j) + (a(i1, j) - a(i, j)) * fx;
    const double hi = a(i, j1) + (a(i1, j1) - a(i, j1)) * fx;
    return lo + (hi - lo) * fy;
}

}  // namespace

Medium make_medium(const LayerBase& base, const LayerOptions& layers, const Terrain& terrain,
                   const MediumOptions& options, const std::string& label)
{
    validate_medium_options(options, label);
    if (base.position.empty() || base.triangles.empty())
        throw InputError(label, "/fog", "the fog has no surface to fill (empty layer base)");
    const Heightfield& hf = terrain.heightfield();
    // Grid over the base's bounds, one terrain cell apart unless told otherwise, at most
    // max_grid_side samples per side; one extra sample around so the border fade reaches 0.
    double spacing = options.grid_spacing > 0.0 ? options.grid_spacing : std::min(hf.dx, hf.dy);
    const double ex = base.max.x - base.min.x, ey = base.max.y - base.min.y;
    spacing = std::max({spacing, ex / (options.max_grid_side - 3), ey / (options.max_grid_side - 3), 1e-6});
    MediumGrid g;
    g.dx = g.dy = spacing;
    g.nx = int(std::ceil(ex / spacing)) + 3;
    g.ny = int(std::ceil(ey / spacing)) + 3;
    g.x0 = base.min.x - spacing;
    g.y0 = base.min.y - spacing;
    const std::size_t n = std::size_t(g.nx) * g.ny;
    g.bottom.assign(n, std::numeric_limits<double>::quiet_NaN());
    g.coverage.assign(n, 0.0);

    // Rasterise the base's triangles in (x, y): bottom = interpolated z, coverage = atlas alpha.
    const auto& P = base.position;
    for (std::size_t t = 0; t + 2 < base.triangles.size(); t += 3) {
        const std::uint32_t ia = base.triangles[t], ib = base.triangles[t + 1], ic = base.triangles[t + 2];
        const glm::dvec3 &a = P[ia], &b = P[ib], &c = P[ic];
        const double area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
        if (std::abs(area) < 1e-12)
            continue;
        const int i0 = std::max(0, int(std::ceil((std::min({a.x, b.x, c.x}) - g.x0) / spacing)));
        const int i1 = std::min(g.nx - 1, int(std::floor((std::max({a.x, b.x, c.x}) - g.x0) / spacing)));
        const int j0 = std::max(0, int(std::ceil((std::min({a.y, b.y, c.y}) - g.y0) / spacing)));
        const int j1 = std::min(g.ny - 1, int(std::floor((std::max({a.y, b.y, c.y}) - g.y0) / spacing)));
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) {
                const double x = g.x0 + i * spacing, y = g.y0 + j * spacing;
                const double wa = ((b.x - x) * (c.y - y) - (c.x - x) * (b.y - y)) / area;
                const double wb = ((c.x - x) * (a.y - y) - (a.x - x) * (c.y - y)) / area;
                const double wc = 1.0 - wa - wb;
                constexpr double eps = -1e-9;  // shared edges: either triangle may claim the sample
                if (wa < eps || wb < eps || wc < eps)
                    continue;
                const std::size_t k = std::size_t(j) * g.nx + i;
                g.bottom[k] = wa * a.z + wb * b.z + wc * c.z;
                g.coverage[k] =
                    atlas_alpha(base.texture, wa * base.atlas_uv[ia] + wb * base.atlas_uv[ib] + wc * base.atlas_uv[ic]);
            }
    }

    g.floor.resize(n);
    g.top.resize(n);
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            const std::size_t k = std::size_t(j) * g.nx + i;
            const double ground = terrain.height(g.x0 + i * spacing, g.y0 + j * spacing);
            if (std::isnan(g.bottom[k])) {  // outside the footprint: no fog, a flat shell on the ground
                g.bottom[k] = g.top[k] = g.floor[k] = ground;
                g.coverage[k] = 0.0;
                continue;
            }
            g.top[k] = g.bottom[k] + layers.thickness;
            g.floor[k] = std::min(std::max(g.bottom[k], ground), g.top[k]);
        }
    return Medium(std::move(g), options, medium_detail(options));
}

}  // namespace kiri::geometry
