#pragma once
// Fog-aware slicing: per screen tile of the froxel volume, the view depths its slices span.
// The Medium's shell (froxel_shell.hpp) is rasterised at the frame's resolution into its
// nearest and farthest depth per pixel (one RG32F target blended with GL_MAX: minus the nearest
// depth, and the farthest; half the blending of two targets, GL_MIN and GL_MAX);
// froxel_tiles.comp reduces them, cut at the frame's depth buffer, to one range per tile. The
// per-pixel depths stay for the apply (froxel_march.glsl).
#include <glm/vec2.hpp>

#include "frame_context.hpp"
#include "froxel_shell.hpp"
#include "shader_program.hpp"

namespace kiri::render::detail {

class FroxelTileBounds {
public:
    //! What bounds the slices of a tile.
    enum class Mode {
        standard = 0,  //!< [near, far] everywhere
        shell = 1,     //!< from the shell's entry to its exit in front of the ground
        ground = 2,    //!< fog anywhere (eye inside the shell): [near, ground]
        haze = 3,      //!< the shell's ranges (if any) and a height fog's: from where the ray
                       //!< comes down to its top (haze_top) to the ground
    };
    FroxelTileBounds();
    //! Uploads the shell mesh (once per medium).
    void set_shell(const ShellMesh& shell);
    //! Rasterises the shell's per-pixel depths when `shell` (or in shell mode); else clears them
    //! to none. Before reduce(), in its own pass (a raster pass, timed apart from the compute).
    void rasterise(const FrameContext& frame, Mode mode, bool shell);
    //! Writes the tiles' ranges and central ground depths into `tiles` (RGBA32F, tiles.x by
    //! tiles.y) from the frame's depth texture and the shell's depths of rasterise().
    //! haze_top: in haze mode, the height above which the height fog adds nothing to see.
    void reduce(const FrameContext& frame, Mode mode, const glm::ivec2& tiles, double near, double far,
                GLuint depth_texture, GLuint tiles_texture, double haze_top = 0.0);
    //! Per pixel of the last rasterise() with the shell (RG32F): minus its nearest view depth
    //! (-3e38: none) and its farthest (0: none).
    GLuint shell_depths() const { return depths_.get(); }

private:
    ShaderProgram shell_program_, reduce_;
    VertexArray vao_;
    Buffer vertices_, indices_;
    GLsizei index_count_ = 0;
    Framebuffer fbo_;
    Texture depths_;
    glm::ivec2 raster_{0};
    void ensure_raster(const glm::ivec2& size);
};

}  // namespace kiri::render::detail
