#include "froxel_shell.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "kiri/geometry/medium/medium.hpp"

namespace kiri::render::detail {

bool ShellMesh::contains(const glm::dvec3& p, double pad) const
{
    if (bx < 1 || by < 1)
        return false;
    const double fx = (p.x - x0) / block_dx, fy = (p.y - y0) / block_dy;
    const double margin_x = pad / block_dx, margin_y = pad / block_dy;
    const int i0 = std::max(0, int(std::floor(fx - margin_x))), i1 = std::min(bx - 1, int(std::floor(fx + margin_x)));
    const int j0 = std::max(0, int(std::floor(fy - margin_y))), j1 = std::min(by - 1, int(std::floor(fy + margin_y)));
    for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
            if (!covered[std::size_t(j) * bx + i])
                continue;
            double lo = std::numeric_limits<double>::infinity(), hi = -lo;
            for (int c = 0; c < 4; ++c) {
                const std::size_t k = std::size_t(j + (c >> 1)) * (bx + 1) + std::size_t(i + (c & 1));
                lo = std::min(lo, corner_floor[k]);
                hi = std::max(hi, corner_top[k]);
            }
            if (p.z >= lo - pad && p.z <= hi + pad)
                return true;
        }
    return false;
}

ShellMesh build_shell_mesh(const geometry::Medium& medium, int max_blocks)
{
    const geometry::MediumGrid& g = medium.grid();
    ShellMesh m;
    const int cells_x = g.nx - 1, cells_y = g.ny - 1;
    if (cells_x < 1 || cells_y < 1)
        return m;
    int block = 1;
    while (double((cells_x + block - 1) / block) * double((cells_y + block - 1) / block) > max_blocks)
        ++block;
    m.bx = (cells_x + block - 1) / block;
    m.by = (cells_y + block - 1) / block;
    m.x0 = g.x0;
    m.y0 = g.y0;
    m.block_dx = block * g.dx;
    m.block_dy = block * g.dy;
    // Per block, over its samples (borders included): highest top, lowest floor, any coverage.
    const std::size_t blocks = std::size_t(m.bx) * m.by;
    std::vector<double> top(blocks, -std::numeric_limits<double>::infinity());
    std::vector<double> floor(blocks, std::numeric_limits<double>::infinity());
    m.covered.assign(blocks, 0);
    for (int bj = 0; bj < m.by; ++bj)
        for (int bi = 0; bi < m.bx; ++bi) {
            const std::size_t b = std::size_t(bj) * m.bx + bi;
            for (int j = bj * block; j <= std::min((bj + 1) * block, cells_y); ++j)
                for (int i = bi * block; i <= std::min((bi + 1) * block, cells_x); ++i) {
                    const std::size_t k = std::size_t(j) * g.nx + i;
                    top[b] = std::max(top[b], g.top[k]);
                    floor[b] = std::min(floor[b], g.floor[k]);
                    m.covered[b] = m.covered[b] || (g.coverage[k] > 0.0 && g.top[k] > g.floor[k]);
                }
        }
    // Corners bound every covered block around them.
    const int cx = m.bx + 1, cy = m.by + 1;
    m.corner_top.assign(std::size_t(cx) * cy, -std::numeric_limits<double>::infinity());
    m.corner_floor.assign(std::size_t(cx) * cy, std::numeric_limits<double>::infinity());
    for (int bj = 0; bj < m.by; ++bj)
        for (int bi = 0; bi < m.bx; ++bi) {
            const std::size_t b = std::size_t(bj) * m.bx + bi;
            if (!m.covered[b])
                continue;
            for (int c = 0; c < 4; ++c) {
                const std::size_t k = std::size_t(bj + (c >> 1)) * cx + std::size_t(bi + (c & 1));
                m.corner_top[k] = std::max(m.corner_top[k], top[b]);
                m.corner_floor[k] = std::min(m.corner_floor[k], floor[b]);
            }
        }
    auto corner_x = [&](int i) { return float(g.x0 + std::min(i * block, cells_x) * g.dx); };
    auto corner_y = [&](int j) { return float(g.y0 + std::min(j * block, cells_y) * g.dy); };
    auto vertex = [&](int i, int j, bool upper) {
        const std::size_t k = std::size_t(j) * cx + i;
        m.positions.insert(m.positions.end(),
                           {corner_x(i), corner_y(j), float(upper ? m.corner_top[k] : m.corner_floor[k])});
        return std::uint32_t(m.positions.size() / 3 - 1);
    };
    auto quad = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
        m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
    };
    auto is_covered = [&](int bi, int bj) {
        return bi >= 0 && bj >= 0 && bi < m.bx && bj < m.by && m.covered[std::size_t(bj) * m.bx + bi];
    };
    for (int bj = 0; bj < m.by; ++bj)
        for (int bi = 0; bi < m.bx; ++bi) {
            if (!is_covered(bi, bj))
                continue;
            for (bool upper : {true, false})
                quad(vertex(bi, bj, upper), vertex(bi + 1, bj, upper), vertex(bi + 1, bj + 1, upper),
                     vertex(bi, bj + 1, upper));
            // Walls where the shell ends: each edge (two corners) from floor to top.
            const int edges[4][5] = {{0, -1, 0, 1, 0}, {0, 1, 0, 1, 1}, {-1, 0, 0, 0, 1}, {1, 0, 1, 1, 1}};
            for (const auto& e : edges) {
                if (is_covered(bi + e[0], bj + e[1]))
                    continue;
                // Corner offsets of the edge: (e[2], e[4]) and (e[3], e[4]) for the horizontal
                // edges, (e[2], 0) and (e[3], 1) for the vertical ones.
                const bool horizontal = e[1] != 0;
                const int ai = bi + e[2], aj = bj + (horizontal ? e[4] : 0);
                const int ci = bi + e[3], cj = bj + (horizontal ? e[4] : 1);
                quad(vertex(ai, aj, false), vertex(ci, cj, false), vertex(ci, cj, true), vertex(ai, aj, true));
            }
        }
    return m;
}

}  // namespace kiri::render::detail
