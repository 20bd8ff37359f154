#pragma once
// The Medium's shell as a closed, conservative triangle mesh for rasterising the depths where
// view rays enter and leave the fog (fog-aware slicing). The grid is coarsened into blocks;
// each block's top is raised to the highest top in it and its floor lowered to the lowest floor,
// through corner values that bound every block they touch, so the coarse shell holds the fine
// one. Blocks without coverage are left out; walls close the shell where they end.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace kiri::geometry {
class Medium;
}

namespace kiri::render::detail {

struct ShellMesh {
    std::vector<float> positions;  // xyz per vertex
    std::vector<std::uint32_t> indices;
    // The coarse grid, for inside tests.
    int bx = 0, by = 0;  // blocks
    double x0 = 0.0, y0 = 0.0, block_dx = 1.0, block_dy = 1.0;
    std::vector<double> corner_top, corner_floor;  // (bx + 1) (by + 1) corners
    std::vector<std::uint8_t> covered;             // bx by blocks

    //! Whether p lies in the coarse shell grown by pad (metres).
    bool contains(const glm::dvec3& p, double pad) const;
};

//! The whole shell's blocks, at most: a full-resolution frame's.
inline constexpr int shell_max_blocks = 65536;

//! At most about max_blocks blocks.
ShellMesh build_shell_mesh(const geometry::Medium& medium, int max_blocks = shell_max_blocks);

}  // namespace kiri::render::detail
