#pragma once
// Internal: filling nodata cells of a grid so heights stay finite.
#include <cstdint>
#include <vector>

namespace kiri::geometry {

// Fills every cell with valid == 0 from the nearest valid cells, by rings ("onion peeling"):
// cells at chessboard distance 1 from valid data take the mean of their valid 8-neighbours,
// then cells at distance 2 the mean of their neighbours filled so far, and so on. A lone hole
// in a plane is refilled exactly; a wide hole gets a smooth-ish extrapolation of its rim.
// valid is left untouched (it still says which cells were invented). Needs one valid cell.
void fill_from_nearest_valid(int nx, int ny, std::vector<double>& z, const std::vector<std::uint8_t>& valid);

}  // namespace kiri::geometry
