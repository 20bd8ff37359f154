#include "kiri/geometry/layers/layer_lod.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include <glm/geometric.hpp>

#include "kiri/geometry/core/error.hpp"

namespace kiri::geometry {
namespace {

// (i, j) on a grid of level n of the point at k / m along side s (corner s -> corner s + 1) and
// d / m inwards: tessellate.cpp's side_param on integers (m divides n).
std::array<int, 2> side_point(int s, int k, int d, int m, int n)
{
    const int t = k * (n / m), e = d * (n / m);
    switch (s) {
    case 0: return {t, e};
    case 1: return {n - e, t};
    case 2: return {n - t, n - e};
    default: return {e, n - t};
    }
}

int smallest_divisor_at_least(int n, int want)
{
    for (int d = std::clamp(want, 1, n); d < n; ++d)
        if (n % d == 0)
            return d;
    return n;
}

}  // namespace

LayerPatchGrid make_layer_patch_grid(const Tessellation& tessellation, const std::vector<glm::dvec3>& position)
{
    const TriMesh& mesh = tessellation.mesh;
    const std::vector<int>& levels = tessellation.patch_level;
    OpenMesh::VPropHandleT<int> patch_id;
    if (levels.empty() || !mesh.get_property_handle(patch_id, patch_id_property) || !mesh.has_vertex_texcoords2D() ||
        position.size() != mesh.n_vertices())
        return {};
    const int n = levels.front();
    if (n < 1 || std::any_of(levels.begin(), levels.end(), [n](int l) { return l != n; }))
        return {};
    const int nf = int(levels.size());
    const std::size_t side = std::size_t(n + 1);
    LayerPatchGrid g;
    g.level = n;
    g.patches = nf;
    constexpr std::uint32_t unset = ~std::uint32_t(0);
    g.vertex.assign(std::size_t(nf) * side * side, unset);
    for (auto vh : mesh.vertices()) {
        const int f = mesh.property(patch_id, vh);
        const auto uv = mesh.texcoord2D(vh);
        const double a = double(uv[0]) * n, b = double(uv[1]) * n;
        const long i = std::lround(a), j = std::lround(b);
        if (f < 0 || f >= nf || std::abs(a - double(i)) > 0.01 || std::abs(b - double(j)) > 0.01 || i < 0 || j < 0 ||
            i > n || j > n)
            return {};
        std::uint32_t& slot = g.vertex[(std::size_t(f) * side + std::size_t(j)) * side + std::size_t(i)];
        if (slot != unset)
            return {};
        slot = std::uint32_t(vh.idx());
    }
    if (std::find(g.vertex.begin(), g.vertex.end(), unset) != g.vertex.end())
        return {};
    // Neighbours across each side: the patches whose side has the same two corner points.
    using Point = std::tuple<double, double, double>;
    const auto key = [&](int f, int s) {
        const auto a = side_point(s, 0, 0, 1, n), b = side_point(s, 1, 0, 1, n);
        const glm::dvec3 p = position[g.at(f, a[0], a[1])], q = position[g.at(f, b[0], b[1])];
        Point u{p.x, p.y, p.z}, v{q.x, q.y, q.z};
        return u < v ? std::pair(u, v) : std::pair(v, u);
    };
    std::map<std::pair<Point, Point>, std::pair<int, int>> first;
    g.neighbour.assign(std::size_t(nf), {-1, -1, -1, -1});
    for (int f = 0; f < nf; ++f)
        for (int s = 0; s < 4; ++s) {
            const auto [it, inserted] = first.try_emplace(key(f, s), f, s);
            if (!inserted) {
                g.neighbour[std::size_t(f)][std::size_t(s)] = it->second.first;
                g.neighbour[std::size_t(it->second.first)][std::size_t(it->second.second)] = f;
            }
        }
    return g;
}

std::vector<int> layer_lod_levels(const LayerBase& base, const glm::dvec3& eye, double pixels_per_radian,
                                  double edge_pixels, double stack_height)
{
    const LayerPatchGrid& g = base.grid;
    if (g.empty())
        return {};
    const int n = g.level;
    std::vector<int> levels(std::size_t(g.patches), n);
    if (!(std::isfinite(pixels_per_radian) && pixels_per_radian > 0.0 && std::isfinite(edge_pixels) &&
          edge_pixels > 0.0 && std::isfinite(stack_height) && std::isfinite(eye.x) && std::isfinite(eye.y) &&
          std::isfinite(eye.z)))
        return levels;
    const int m = n / 2;
    for (int f = 0; f < g.patches; ++f) {
        const glm::dvec3 p[5] = {base.position[g.at(f, 0, 0)], base.position[g.at(f, n, 0)],
                                 base.position[g.at(f, n, n)], base.position[g.at(f, 0, n)],
                                 base.position[g.at(f, m, m)]};
        glm::dvec3 centre(0.0);
        for (const glm::dvec3& q : p)
            centre += 0.2 * q;
        double radius = 0.0;
        for (const glm::dvec3& q : p)
            radius = std::max(radius, glm::length(q - centre));
        // The stack rises above the base: the sphere holds it, and half a cell more for the
        // surface's bulge between the five points.
        radius = radius * (1.0 + 0.5 / n) + std::abs(stack_height);
        const double distance = glm::length(centre - eye) - radius;
        if (!(distance > 0.0))
            continue;  // the eye is at the patch: full level
        const double pixels = 2.0 * radius * pixels_per_radian / distance;
        const double want = std::ceil(pixels / edge_pixels);
        levels[std::size_t(f)] = want >= n ? n : smallest_divisor_at_least(n, std::max(1, int(want)));
    }
    return levels;
}

std::vector<std::uint32_t> layer_lod_triangles(const LayerPatchGrid& g, const std::vector<int>& levels)
{
    if (int(levels.size()) != g.patches)
        throw InputError("", "layers/lod", "one level per patch is needed");
    const int n = g.level;
    for (int l : levels)
        if (l < 1 || l > n || n % l != 0)
            throw InputError("", "layers/lod", "a patch's level must divide the tessellation's level");
    std::vector<std::uint32_t> out;
    for (int f = 0; f < g.patches; ++f) {
        const int level = levels[std::size_t(f)];
        int sides[4];
        bool all_one = level == 1;
        for (int s = 0; s < 4; ++s) {
            const int other = g.neighbour[std::size_t(f)][std::size_t(s)];
            sides[s] = other < 0 ? level : std::max(level, levels[std::size_t(other)]);
            all_one = all_one && sides[s] == 1;
        }
        const auto v = [&](std::array<int, 2> ij) { return g.at(f, ij[0], ij[1]); };
        const auto tri = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) { out.insert(out.end(), {a, b, c}); };
        if (all_one) {  // tessellate.cpp's patch of level 1
            tri(v({0, 0}), v({n, 0}), v({n, n}));
            tri(v({0, 0}), v({n, n}), v({0, n}));
            continue;
        }
        // The inner grid at the patch's level (at least 2 cells, a divisor of n), the side strips
        // zipped from each side's points to the inner ring's: tessellate.cpp's build() on the
        // grid's points.
        const int inner = level >= 2 ? level : smallest_divisor_at_least(n, 2);
        const int step = n / inner;
        const auto in = [&](int a, int b) { return g.at(f, a * step, b * step); };
        for (int b = 1; b < inner - 1; ++b)
            for (int a = 1; a < inner - 1; ++a) {
                tri(in(a, b), in(a + 1, b), in(a + 1, b + 1));
                tri(in(a, b), in(a + 1, b + 1), in(a, b + 1));
            }
        for (int s = 0; s < 4; ++s) {
            const int l = sides[s];
            const int last = inner - 2;  // inner side points m = 1 .. inner - 1, indexed 0 .. last
            int k = 0, m = 0;
            while (k < l || m < last) {
                // Outer point k + 1 at (k + 1) / l, inner point m + 1 at (m + 2) / inner.
                const bool outer = m == last || (k < l && std::int64_t(k + 1) * inner <= std::int64_t(m + 2) * l);
                if (outer) {
                    tri(v(side_point(s, k, 0, l, n)), v(side_point(s, k + 1, 0, l, n)),
                        v(side_point(s, m + 1, 1, inner, n)));
                    ++k;
                } else {
                    tri(v(side_point(s, k, 0, l, n)), v(side_point(s, m + 2, 1, inner, n)),
                        v(side_point(s, m + 1, 1, inner, n)));
                    ++m;
                }
            }
        }
    }
    return out;
}

}  // namespace kiri::geometry
