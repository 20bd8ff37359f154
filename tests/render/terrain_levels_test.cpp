// The terrain grid's coarser levels (render/src/terrain_levels.hpp): a level covers the grid's
// rectangle exactly, counter-clockwise, watertight inside (each inner edge shared by two
// triangles in opposite directions: no T-junction), and its border is the full grid's, sample by
// sample, so the surround's first ring meets it without a crack. The surround's levels keep every
// ring and meet the grid's level without a crack: grid and surround together tile the whole
// tensor grid watertight, its outer border at the level's samples.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <utility>
#include <vector>

#include "terrain_levels.hpp"

namespace {

using kiri::render::detail::grid_level_indices;
using kiri::render::detail::GridLayout;
using kiri::render::detail::surround_level_indices;

struct Checked {
    double area = 0.0;
    int degenerate = 0, clockwise = 0, unmatched_inner = 0;
    std::map<std::pair<int, int>, int> border;  // edges used once: (from, to) sample ids
};

// Samples are ids j * nx + i of the grid alone (offset 2, row nx + 4 in the vertex array).
Checked check(const GridLayout& g, const std::vector<std::uint32_t>& indices)
{
    const auto sample = [&](std::uint32_t v) {
        const int j = int(v) / g.row - g.offset, i = int(v) % g.row - g.offset;
        return std::pair{i, j};
    };
    Checked c;
    std::map<std::pair<int, int>, int> directed;
    for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
        const auto [x0, y0] = sample(indices[t]);
        const auto [x1, y1] = sample(indices[t + 1]);
        const auto [x2, y2] = sample(indices[t + 2]);
        const double a = 0.5 * double((x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0));
        c.area += a;
        c.degenerate += a == 0.0;
        c.clockwise += a < 0.0;
        for (int e = 0; e < 3; ++e) {
            const auto [p, q] = std::pair{sample(indices[t + e]), sample(indices[t + (e + 1) % 3])};
            ++directed[{p.second * g.nx + p.first, q.second * g.nx + q.first}];
        }
    }
    for (const auto& [edge, n] : directed) {
        const int back = directed.count({edge.second, edge.first}) ? directed.at({edge.second, edge.first}) : 0;
        if (back == 0)
            c.border[edge] = n;
        else if (n != 1 || back != 1)
            ++c.unmatched_inner;
    }
    return c;
}

// The full grid's border, counter-clockwise, one edge per pair of neighbouring samples.
std::map<std::pair<int, int>, int> full_border(const GridLayout& g)
{
    std::map<std::pair<int, int>, int> b;
    const auto id = [&](int i, int j) { return j * g.nx + i; };
    for (int i = 0; i + 1 < g.nx; ++i) {
        b[{id(i, 0), id(i + 1, 0)}] = 1;
        b[{id(i + 1, g.ny - 1), id(i, g.ny - 1)}] = 1;
    }
    for (int j = 0; j + 1 < g.ny; ++j) {
        b[{id(g.nx - 1, j), id(g.nx - 1, j + 1)}] = 1;
        b[{id(0, j + 1), id(0, j)}] = 1;
    }
    return b;
}

TEST(TerrainLevels, StrideOneIsTheFullGrid)
{
    const GridLayout g{5, 4, 9, 2};
    std::vector<std::uint32_t> expected;
    for (int j = 0; j + 1 < g.ny; ++j)
        for (int i = 0; i + 1 < g.nx; ++i)
            expected.insert(expected.end(),
                            {g.vertex(i, j), g.vertex(i + 1, j), g.vertex(i + 1, j + 1), g.vertex(i, j),
                             g.vertex(i + 1, j + 1), g.vertex(i, j + 1)});
    EXPECT_EQ(grid_level_indices(g, 1), expected);
}

TEST(TerrainLevels, CoarseLevelsCoverTheGridWatertightWithItsWholeBorder)
{
    for (const auto& [nx, ny] : {std::pair{13, 10}, {9, 9}, {17, 5}, {3, 3}, {2, 7}, {403, 344}})
        for (int stride : {2, 4, 8}) {
            const GridLayout g{nx, ny, nx + 4, 2};
            const std::vector<std::uint32_t> level = grid_level_indices(g, stride);
            const Checked c = check(g, level);
            EXPECT_DOUBLE_EQ(c.area, double(nx - 1) * (ny - 1)) << nx << "x" << ny << " / " << stride;
            EXPECT_EQ(c.degenerate, 0) << nx << "x" << ny << " / " << stride;
            EXPECT_EQ(c.clockwise, 0) << nx << "x" << ny << " / " << stride;
            EXPECT_EQ(c.unmatched_inner, 0) << nx << "x" << ny << " / " << stride;
            EXPECT_EQ(c.border, full_border(g)) << nx << "x" << ny << " / " << stride;
        }
}

TEST(TerrainLevels, ALevelDrawsAboutOneCellInStrideSquared)
{
    const GridLayout g{403, 344, 407, 2};
    const double full = double(grid_level_indices(g, 1).size());
    for (int stride : {2, 4, 8}) {
        const double ratio = full / double(grid_level_indices(g, stride).size());
        // The border's fans add a few per cent; fewer than stride^2 times fewer, more than 70 % of it (48 at 8, the grid 403 x 344).
        EXPECT_GT(ratio, 0.7 * stride * stride) << stride;
        EXPECT_LT(ratio, double(stride * stride)) << stride;
    }
}

// The whole vertex array (grid and rings) as one grid: the layout its check() reads ids in.
GridLayout tensor(const GridLayout& g) { return {g.nx + 2 * g.offset, g.ny + 2 * g.offset, g.nx + 2 * g.offset, 0}; }

std::vector<std::uint32_t> level_with_surround(const GridLayout& g, int stride)
{
    std::vector<std::uint32_t> all = grid_level_indices(g, stride);
    const std::vector<std::uint32_t> outer = surround_level_indices(g, stride);
    all.insert(all.end(), outer.begin(), outer.end());
    return all;
}

TEST(TerrainLevels, StrideOneIsTheFullSurround)
{
    // Every cell of the rings, row by row, split as the grid's cells are.
    const GridLayout g{5, 4, 5 + 6, 3};
    std::vector<std::uint32_t> expected;
    const GridLayout t = tensor(g);
    for (int j = 0; j + 1 < t.ny; ++j)
        for (int i = 0; i + 1 < t.nx; ++i) {
            const bool in_grid = i >= g.offset && i + 1 < g.offset + g.nx && j >= g.offset && j + 1 < g.offset + g.ny;
            if (!in_grid)
                expected.insert(expected.end(),
                                {t.vertex(i, j), t.vertex(i + 1, j), t.vertex(i + 1, j + 1), t.vertex(i, j),
                                 t.vertex(i + 1, j + 1), t.vertex(i, j + 1)});
        }
    EXPECT_EQ(surround_level_indices(g, 1), expected);
}

TEST(TerrainLevels, ASurroundLevelMeetsTheGridsLevelWatertightAndKeepsEveryRing)
{
    for (const auto& [nx, ny] : {std::pair{13, 10}, {9, 9}, {17, 5}, {3, 3}, {2, 7}, {203, 144}})
        for (int rings : {1, 4})
            for (int stride : {1, 2, 4, 8}) {
                const GridLayout g{nx, ny, nx + 2 * rings, rings};
                const GridLayout t = tensor(g);
                const std::vector<std::uint32_t> level = level_with_surround(g, stride);
                const Checked c = check(t, level);
                EXPECT_DOUBLE_EQ(c.area, double(t.nx - 1) * (t.ny - 1)) << nx << "x" << ny << " / " << stride;
                EXPECT_EQ(c.degenerate, 0) << nx << "x" << ny << " / " << stride;
                EXPECT_EQ(c.clockwise, 0) << nx << "x" << ny << " / " << stride;
                EXPECT_EQ(c.unmatched_inner, 0) << nx << "x" << ny << " / " << stride;
                // Every ring at each of the level's samples along the grid's sides: the vertex
                // (k + s, r) below the grid, and the same on the other three sides.
                std::set<std::uint32_t> used(level.begin(), level.end());
                // The level's samples: 0, s, 2 s, ..., n - 1, the stride halved until two coarse
                // cells fit each way (terrain_levels.hpp).
                int s = stride;
                while (s > 1 && (s >= nx - 1 || s >= ny - 1))
                    s /= 2;
                std::set<int> xs{nx - 1}, ys{ny - 1};
                for (int i = 0; i < nx - 1; i += s)
                    xs.insert(i);
                for (int j = 0; j < ny - 1; j += s)
                    ys.insert(j);
                for (int r = 0; r < rings; ++r) {
                    for (int i : xs)
                        for (int j : {r, t.ny - 1 - r})
                            EXPECT_EQ(used.count(t.vertex(rings + i, j)), 1u) << nx << "x" << ny << " / " << stride;
                    for (int j : ys)
                        for (int i : {r, t.nx - 1 - r})
                            EXPECT_EQ(used.count(t.vertex(i, rings + j)), 1u) << nx << "x" << ny << " / " << stride;
                }
                // No crack: every edge used once lies on the tensor's outer border (a T-junction
                // where the strip meets the grid's level leaves edges used once inside), and
                // the border runs round once: each of its vertices left as often as entered.
                std::map<int, int> out_of, into;
                const auto on_side = [&](int a, int b) {
                    const int ia = a % t.nx, ja = a / t.nx, ib = b % t.nx, jb = b / t.nx;
                    return (ja == jb && (ja == 0 || ja == t.ny - 1)) || (ia == ib && (ia == 0 || ia == t.nx - 1));
                };
                int inside = 0;
                for (const auto& [edge, n] : c.border) {
                    out_of[edge.first] += n;
                    into[edge.second] += n;
                    inside += !on_side(edge.first, edge.second);
                }
                EXPECT_EQ(inside, 0) << nx << "x" << ny << " / " << stride;
                EXPECT_EQ(out_of, into) << nx << "x" << ny << " / " << stride;
            }
}

TEST(TerrainLevels, ASurroundLevelDrawsItsRingsAtTheLevelsSamples)
{
    // Jacksboro's grid (344 x 403) and its 21 rings: 66,108 triangles of surround at every
    // sample, 12,726 at the 8th level (the preview's floor), whose grid has 5,688. Along the
    // sides stride times fewer; the corners' ring-by-ring cells and the fans of the strip next to
    // the grid stay.
    const GridLayout g{344, 403, 344 + 2 * 21, 21};
    const double full = double(surround_level_indices(g, 1).size());
    EXPECT_EQ(full, 3.0 * 66108);
    EXPECT_EQ(surround_level_indices(g, 8).size(), 3u * 12726);
    for (int stride : {2, 4, 8}) {
        const double ratio = full / double(surround_level_indices(g, stride).size());
        EXPECT_GT(ratio, 0.6 * stride) << stride;
        EXPECT_LT(ratio, double(stride)) << stride;
    }
}

}  // namespace
