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

// At least two coarse cells each way, so that no cell of the grid has border on opposite sides
// and every border cell has a corner off the border to fan from.
int usable_stride(const GridLayout& grid, int stride)
{
    stride = std::max(stride, 1);
    while (stride > 1 && (stride >= grid.nx - 1 || stride >= grid.ny - 1))
        stride /= 2;
    return stride;
}

// The cell between the vertex array's columns i0 < i1 and rows j0 < j1 (`vertex(i, j)`): two
// triangles split along (i0, j0)-(i1, j1) where none of its sides is `fine` (south, east, north,
// west) or it is one cell; else its boundary counter-clockwise, every sample of a fine side and
// only the corners of the others, as a fan from the corner whose two sides are coarse (the cell
// is convex, and no triangle of the fan lies along a straight run of fine samples).
template <class Vertex>
void add_cell(std::vector<std::uint32_t>& out, const Vertex& vertex, int i0, int i1, int j0, int j1,
              const bool (&fine)[4])
{
    const bool south = fine[0], east = fine[1], north = fine[2], west = fine[3];
    if ((i1 - i0 == 1 && j1 - j0 == 1) || !(south || north || west || east)) {
        const std::uint32_t p = vertex(i0, j0), q = vertex(i1, j0), r = vertex(i1, j1), s = vertex(i0, j1);
        out.insert(out.end(), {p, q, r, p, r, s});
        return;
    }
    std::vector<std::uint32_t> ring;
    for (int i = i0; i < i1; i += south ? 1 : i1 - i0)
        ring.push_back(vertex(i, j0));
    for (int j = j0; j < j1; j += east ? 1 : j1 - j0)
        ring.push_back(vertex(i1, j));
    for (int i = i1; i > i0; i -= north ? 1 : i1 - i0)
        ring.push_back(vertex(i, j1));
    for (int j = j1; j > j0; j -= west ? 1 : j1 - j0)
        ring.push_back(vertex(i0, j));
    const std::uint32_t corners[4] = {vertex(i0, j0), vertex(i1, j0), vertex(i1, j1), vertex(i0, j1)};
    const bool coarse_corner[4] = {!south && !west, !south && !east, !north && !east, !north && !west};
    const int apex = int(std::find(coarse_corner, coarse_corner + 4, true) - coarse_corner);
    const std::size_t start = std::size_t(std::find(ring.begin(), ring.end(), corners[apex]) - ring.begin());
    const std::size_t n = ring.size();
    for (std::size_t k = 1; k + 1 < n; ++k)
        out.insert(out.end(), {corners[apex], ring[(start + k) % n], ring[(start + k + 1) % n]});
}

}  // namespace

std::vector<std::uint32_t> grid_level_indices(const GridLayout& grid, int stride)
{
    std::vector<std::uint32_t> out;
    if (grid.nx < 2 || grid.ny < 2)
        return out;
    stride = usable_stride(grid, stride);
    const std::vector<int> xs = level_samples(grid.nx, stride), ys = level_samples(grid.ny, stride);
    out.reserve((xs.size() - 1) * (ys.size() - 1) * 6);
    const auto vertex = [&](int i, int j) { return grid.vertex(i, j); };
    for (std::size_t b = 0; b + 1 < ys.size(); ++b)
        for (std::size_t a = 0; a + 1 < xs.size(); ++a) {
            const int i0 = xs[a], i1 = xs[a + 1], j0 = ys[b], j1 = ys[b + 1];
            const bool border[4] = {j0 == 0, i1 == grid.nx - 1, j1 == grid.ny - 1, i0 == 0};
            add_cell(out, vertex, i0, i1, j0, j1, border);
        }
    return out;
}

std::vector<std::uint32_t> surround_level_indices(const GridLayout& grid, int stride)
{
    std::vector<std::uint32_t> out;
    const int k = grid.offset;
    if (grid.nx < 2 || grid.ny < 2 || k < 1)
        return out;
    stride = usable_stride(grid, stride);
    // The vertex array's columns (and rows): the rings before the grid, the level's samples of
    // it, the rings after; every ring, all the way round.
    const auto columns = [&](int n) {
        std::vector<int> c;
        for (int r = 0; r < k; ++r)
            c.push_back(r);
        for (int s : level_samples(n, stride))
            c.push_back(k + s);
        for (int r = 1; r <= k; ++r)
            c.push_back(k + n - 1 + r);
        return c;
    };
    const std::vector<int> xs = columns(grid.nx), ys = columns(grid.ny);
    const auto vertex = [&](int i, int j) { return std::uint32_t(j * grid.row + i); };
    const int grid_i0 = k, grid_i1 = k + grid.nx - 1, grid_j0 = k, grid_j1 = k + grid.ny - 1;
    for (std::size_t b = 0; b + 1 < ys.size(); ++b)
        for (std::size_t a = 0; a + 1 < xs.size(); ++a) {
            const int i0 = xs[a], i1 = xs[a + 1], j0 = ys[b], j1 = ys[b + 1];
            const bool inside = i0 >= grid_i0 && i1 <= grid_i1 && j0 >= grid_j0 && j1 <= grid_j1;
            if (inside)
                continue;  // the grid's level
            // A side the grid's border runs along takes each of its samples, as the level does.
            const bool along_x = i0 >= grid_i0 && i1 <= grid_i1, along_y = j0 >= grid_j0 && j1 <= grid_j1;
            const bool fine[4] = {along_x && j0 == grid_j1, along_y && i1 == grid_i0, along_x && j1 == grid_j0,
                                  along_y && i0 == grid_i1};
            add_cell(out, vertex, i0, i1, j0, j1, fine);
        }
    return out;
}

}  // namespace kiri::render::detail
