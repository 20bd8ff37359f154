// What FroxelPass's two sources share: froxel_pass.cpp (the pass, its volumes and the apply)
// and froxel_volume_passes.cpp (the passes that fill the volume each update): the texture units,
// the stages' timers and the volume's textures.
#pragma once

#include <glm/vec3.hpp>

#include "froxel_pass.hpp"
#include "gl_objects.hpp"

namespace kiri::render::detail {
namespace froxel_parts {

// Texture units: the apply's (8..10) stay clear of the terrain's and layers' (0..2).
// Unit 10 is the sun's shadow map's (shadow_map_unit).
inline constexpr int unit_tiles = 8, unit_volume = 9, unit_medium = 11;  // 11, 12
inline constexpr int unit_density = 13, unit_light = 14, unit_history = 15, unit_history_tiles = 7;
inline constexpr int unit_shell_depths = 5;
inline constexpr int unit_sun = 16;           // 16, 17, 18
inline constexpr int unit_light_volume = 19;  // and 21: the cells' floors (LightVolumeTexture::bind)
// The apply's work in three timers (a GL timer query cannot nest): the grids and the marches of
// the pixels the volume does not resolve, the split pixels' samples' marches, the frame's fog.
// The shell's rasterisation is timed apart from the tiles' reduction: a raster pass and a
// compute pass, which a data-centre GPU runs at very different speeds (docs/speed.md).
enum Stage {
    shell_stage,
    tiles,
    density,
    lighting,
    temporal,
    integrate,
    classify,
    marches,
    splits,
    apply_stage,
    stage_count
};

// A dispatch whose groups a list's header counts (the list bound as the program's storage
// buffer 0 meanwhile), then the barrier that lets the next pass read what it wrote.
inline void dispatch_listed(GLuint list)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, list);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, list);
    glDispatchComputeIndirect(0);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

}  // namespace froxel_parts

struct FroxelPass::Volumes {
    glm::ivec3 size{0};
    Texture density, light, resolved[2], integrated, tiles[2];
    Buffer fog_tiles;  // the tiles with fog and the dispatch over their froxels (froxel_fog_tiles.glsl)
};

}  // namespace kiri::render::detail
