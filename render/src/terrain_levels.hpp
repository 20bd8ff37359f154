#pragma once
// Coarser levels of the terrain's grid for frames drawn small (the preview while the view moves):
// triangles over every stride-th sample of the grid, its vertices the full grid's own (no new
// vertex buffer), so a level costs only its indices. The grid's border keeps every sample: the
// surround's first ring meets each of them, so a coarse level leaves no crack at the edge.
#include <cstdint>
#include <vector>

namespace kiri::render::detail {

//! Where the grid's samples lie in the vertex array: sample (i, j) of the nx x ny grid is vertex
//! (j + offset) * row + i + offset (the surround's rings around it take `offset` rows and columns).
struct GridLayout {
    int nx = 0, ny = 0;
    int row = 0, offset = 0;
    std::uint32_t vertex(int i, int j) const { return std::uint32_t((j + offset) * row + i + offset); }
};

//! The grid's triangles at one sample in `stride` (>= 1; 1 is the full grid, two triangles a
//! cell split along (i, j)-(i + 1, j + 1)), counter-clockwise seen from above: coarse cells
//! between the samples i = 0, stride, 2 stride, ..., nx - 1 (and so in j); a coarse cell on the
//! border takes every sample of its border sides, as a fan from its corner off the border. A
//! stride that would leave fewer than two coarse cells across or down is halved until it does not.
std::vector<std::uint32_t> grid_level_indices(const GridLayout& grid, int stride);

//! The surround's triangles around grid_level_indices(grid, stride): the `grid.offset` rings on
//! every side, all of them (the surround's smoothstep lies in them), but along the grid's sides
//! only at the level's samples (the full mesh draws a cell of each ring per sample of the border:
//! eleven times the triangles of the 8th level of Jacksboro's grid). The strip next to the grid
//! takes every sample of the grid's border, as a fan, so it meets the level without a crack;
//! stride 1 is the full tensor grid's surround.
std::vector<std::uint32_t> surround_level_indices(const GridLayout& grid, int stride);

}  // namespace kiri::render::detail
