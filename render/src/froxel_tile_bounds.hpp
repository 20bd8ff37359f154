#pragma once
// Fog-aware slicing: per screen tile of the froxel volume, the view depths its slices span.
// The terrain's depth and the Medium's shell (froxel_shell.hpp: nearest and farthest depth by
// GL_MIN / GL_MAX blending) are rasterised at a few samples per tile; froxel_tiles.comp reduces
// them to one range per tile.
#include <glm/mat4x4.hpp>

#include "frame_context.hpp"
#include "froxel_shell.hpp"
#include "shader_program.hpp"

namespace kiri::render::detail {

class TerrainPass;

class FroxelTileBounds {
public:
    //! What bounds the slices of a tile.
    enum class Mode {
        standard = 0,  //!< [near, far] everywhere
        shell = 1,     //!< from the shell's entry to its exit in front of the ground
        ground = 2,    //!< fog anywhere (eye inside the shell, height fog): [near, ground]
    };
    FroxelTileBounds();
    //! Uploads the shell mesh (once per medium).
    void set_shell(const ShellMesh& shell);
    //! Writes the tiles' ranges and central ground depths into `tiles` (RGBA32F, tiles.x by tiles.y).
    void update(const FrameContext& frame, const TerrainPass& terrain, Mode mode, const glm::ivec2& tiles,
                double near, double far, GLuint tiles_texture);

private:
    ShaderProgram shell_program_, depth_program_, reduce_;
    VertexArray vao_;
    Buffer vertices_, indices_;
    GLsizei index_count_ = 0;
    Framebuffer fbo_;
    Texture first_, last_, ground_;
    Framebuffer centres_fbo_;  // the ground on the tiles' central rays: one sample per tile
    Texture centres_;
    glm::ivec2 tiles_{0};
    glm::ivec2 raster_{0};
    void ensure_raster(const glm::ivec2& size);
};

}  // namespace kiri::render::detail
