#pragma once
// Internal: filling nodata cells of a grid so heights stay finite and smooth.
#include <cstdint>
#include <vector>

namespace kiri::geometry {

// Fills every cell with valid == 0 by a membrane over the valid cells: the discrete harmonic
// interpolant (each filled cell the mean of its 4-neighbours; the valid cells fixed; no flux
// through the grid's border), so a hole gets no spike, no crease and no value outside the
// range of its rim (maximum principle), and a plane is refilled exactly. Solved coarse to fine
// (the grid halved until it has no void, each level started from the coarser one and relaxed by
// Gauss-Seidel), so wide voids such as a nodata border cost O(cells), not O(cells * width).
// valid is left untouched (it still says which cells were invented). Needs one valid cell.
void fill_voids_smoothly(int nx, int ny, std::vector<double>& z, const std::vector<std::uint8_t>& valid);

}  // namespace kiri::geometry
