#include "terrain_levels.hpp"

#include <algorithm>

namespace kiri::render::detail {
namespace {

// 0, stride, 2 stride, ..., n - 1.
std::vector<int> level_samples(int n, int stride)
{
    std::vector<int> s;
    for (int i = 0; i < n - 1; i += stride)
        s.push_back(i);
    s.push_back(n - 1);
    return s;
}

}  // namespace

std::vector<std::uint32_t> grid_level_indices(const GridLayout& grid, int stride)
{
    std::vector<std::uint32_t> out;
    if (grid.nx < 2 || grid.ny < 2)
        return out;
    // At least two coarse cells each way, so that no cell has border on opposite sides and every
    // border cell has a corner off the border to fan from.
    stride = std::max(stride, 1);
    while (stride > 1 && (stride >= grid.nx - 1 || stride >= grid.ny - 1))
        stride /= 2;
    const std::vector<int> xs = level_samples(grid.nx, stride), ys = level_samples(grid.ny, stride);
    out.reserve((xs.size() - 1) * (ys.size() - 1) * 6);
    std::vector<std::uint32_t> ring;
    for (std::size_t b = 0; b + 1 < ys.size(); ++b)
        for (std::size_t a = 0; a + 1 < xs.size(); ++a) {
            const int i0 = xs[a], i1 = xs[a + 1], j0 = ys[b], j1 = ys[b + 1];
            const bool south = j0 == 0, north = j1 == grid.ny - 1, west = i0 == 0, east = i1 == grid.nx - 1;
            const bool plain = (i1 - i0 == 1 && j1 - j0 == 1) || !(south || north || west || east);
            if (plain) {  // two triangles, split as the full grid's cells are
                const std::uint32_t p = grid.vertex(i0, j0), q = grid.vertex(i1, j0), r = grid.vertex(i1, j1),
                                    s = grid.vertex(i0, j1);
                out.insert(out.end(), {p, q, r, p, r, s});
                continue;
            }
            // The cell's boundary counter-clockwise from its south-west corner, every sample of a
            // border side, only the corners of an inner one.
            ring.clear();
            for (int i = i0; i < i1; i += south ? 1 : i1 - i0)
                ring.push_back(grid.vertex(i, j0));
            for (int j = j0; j < j1; j += east ? 1 : j1 - j0)
                ring.push_back(grid.vertex(i1, j));
            for (int i = i1; i > i0; i -= north ? 1 : i1 - i0)
                ring.push_back(grid.vertex(i, j1));
            for (int j = j1; j > j0; j -= west ? 1 : j1 - j0)
                ring.push_back(grid.vertex(i0, j));
            // A fan from the corner whose two sides are inner ones: the cell is convex, and no
            // triangle of the fan lies along a straight run of border samples.
            const std::uint32_t corners[4] = {grid.vertex(i0, j0), grid.vertex(i1, j0), grid.vertex(i1, j1),
                                              grid.vertex(i0, j1)};
            const bool inner_corner[4] = {!south && !west, !south && !east, !north && !east, !north && !west};
            const int apex = int(std::find(inner_corner, inner_corner + 4, true) - inner_corner);
            const std::size_t start = std::size_t(std::find(ring.begin(), ring.end(), corners[apex]) - ring.begin());
            const std::size_t n = ring.size();
            for (std::size_t k = 1; k + 1 < n; ++k) {
                const std::uint32_t v1 = ring[(start + k) % n], v2 = ring[(start + k + 1) % n];
                out.insert(out.end(), {corners[apex], v1, v2});
            }
        }
    return out;
}

}  // namespace kiri::render::detail
