// The Medium's shell as the froxels rasterise it (render/src/froxel_shell.hpp): a coarse block
// mesh that holds the fine shell, and the coarser shells of the preview's moving frames (a
// quarter of the blocks per halving of the froxel resolution) hold it too, so a moving frame's
// rays lose no fog to them.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "froxel_shell.hpp"
#include "kiri/geometry/medium/medium.hpp"

namespace {

namespace g = kiri::geometry;
using kiri::render::detail::build_shell_mesh;
using kiri::render::detail::shell_max_blocks;
using kiri::render::detail::ShellMesh;

// A fog lake over rolling ground on a 301 x 301 grid of 10 m: its floor follows the ground,
// its top a level with ripples, its coverage ends in a ring. Many blocks, none alike.
g::Medium rolling_lake()
{
    g::MediumGrid grid;
    grid.nx = grid.ny = 301;
    grid.x0 = grid.y0 = -1500.0;
    grid.dx = grid.dy = 10.0;
    const std::size_t n = std::size_t(grid.nx) * grid.ny;
    grid.floor.resize(n);
    grid.bottom.resize(n);
    grid.top.resize(n);
    grid.coverage.resize(n);
    for (int j = 0; j < grid.ny; ++j)
        for (int i = 0; i < grid.nx; ++i) {
            const double x = grid.x0 + i * grid.dx, y = grid.y0 + j * grid.dy;
            const std::size_t k = std::size_t(j) * grid.nx + i;
            const double ground = 40.0 * std::sin(x / 170.0) * std::cos(y / 230.0);
            const double top = 60.0 + 8.0 * std::sin(x / 37.0 + y / 53.0);
            const double r = std::hypot(x, y);
            grid.floor[k] = grid.bottom[k] = ground;
            grid.coverage[k] = r < 1300.0 && top > ground ? 1.0 : 0.0;
            grid.top[k] = grid.coverage[k] > 0.0 ? top : ground;
        }
    g::MediumOptions o;
    o.extinction = 0.01;
    return g::Medium(std::move(grid), o, g::MediumDetail{});
}

int blocks(const ShellMesh& m) { return m.bx * m.by; }

TEST(FroxelShell, EachCoarserShellHasAQuarterOfTheBlocksAndHoldsTheFinerOne)
{
    const g::Medium lake = rolling_lake();
    std::vector<ShellMesh> shells;
    for (int k = 0; k <= 3; ++k)  // the froxel resolution's steps: 1, 1/2, 1/4, 1/8
        shells.push_back(build_shell_mesh(lake, shell_max_blocks >> (2 * k)));
    // 300 x 300 cells: blocks of 2, 3, 5, 10 cells (at most 65536, 16384, 4096, 1024 blocks).
    EXPECT_EQ(blocks(shells[0]), 150 * 150);
    EXPECT_EQ(blocks(shells[1]), 100 * 100);
    EXPECT_EQ(blocks(shells[2]), 60 * 60);
    EXPECT_EQ(blocks(shells[3]), 30 * 30);
    for (int k = 1; k <= 3; ++k)
        EXPECT_LT(shells[k].indices.size(), shells[k - 1].indices.size()) << k;

    // Points of the fog (inside the fine grid's shell: between floor and top where covered)
    // lie inside every shell, the coarsest too.
    std::mt19937 random(7);
    std::uniform_real_distribution<double> across(-1500.0, 1500.0), up(0.0, 1.0);
    int inside = 0;
    for (int s = 0; s < 20000; ++s) {
        const double x = across(random), y = across(random);
        const g::MediumColumn c = lake.column(x, y);
        if (!(c.coverage > 0.0) || !(c.top > c.floor))
            continue;
        const glm::dvec3 p(x, y, c.floor + up(random) * (c.top - c.floor));
        ++inside;
        for (int k = 0; k <= 3; ++k)
            ASSERT_TRUE(shells[k].contains(p, 0.0)) << "shell " << k << " misses " << x << ", " << y << ", " << p.z;
    }
    EXPECT_GT(inside, 5000);
    // And the coarsest takes in air the fine one does not (it is coarser, not the same).
    int air = 0;
    for (int s = 0; s < 20000; ++s) {
        const glm::dvec3 p(across(random), across(random), -40.0 + 120.0 * up(random));
        air += shells[3].contains(p, 0.0) && !shells[0].contains(p, 0.0);
    }
    EXPECT_GT(air, 100);
}

}  // namespace
