#pragma once
//! \file layer_patch_grid.hpp
//! The layer base's vertices as a grid per patch: with a uniform tessellation of level N every
//! patch holds the (N + 1)^2 points (i / N, j / N) of its own (u, v), each its own vertex. The
//! level of detail (layer_lod.hpp) draws coarser grids of the same vertices.
#include <array>
#include <cstdint>
#include <vector>

namespace kiri::geometry {

struct LayerPatchGrid {
    int level = 0;  //!< N; 0: no grid (an adaptive tessellation)
    int patches = 0;
    //! vertex[(f (N + 1) + j) (N + 1) + i]: patch f's vertex at (u, v) = (i, j) / N.
    std::vector<std::uint32_t> vertex;
    //! Per patch and side (0: v = 0, 1: u = 1, 2: v = 1, 3: u = 0), the patch across it, or -1.
    std::vector<std::array<int, 4>> neighbour;
    bool empty() const { return level == 0; }
    std::uint32_t at(int f, int i, int j) const
    {
        return vertex[(std::size_t(f) * std::size_t(level + 1) + std::size_t(j)) * std::size_t(level + 1) +
                      std::size_t(i)];
    }
};

}  // namespace kiri::geometry
