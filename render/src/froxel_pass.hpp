#pragma once
// Froxel volumetric fog (Wronski 2014, with Hillaire's energy-conserving integration and
// fog-aware slicing; docs/froxel.md). Per frame, only when the view, the sun or the fog
// changed (and until the temporal history has settled):
//   tiles     the depths each screen tile's slices span (froxel_tile_bounds.hpp)
//   density   extinction per froxel from the Medium and the height fog (froxel_density.comp)
//   lighting  in-scattering per froxel: sun through the terrain's ESM and the fog, sky ambient,
//             Henyey-Greenstein (froxel_lighting.comp)
//   temporal  reprojected, clamped history (froxel_temporal.comp), when on
//   integrate front to back through the slices (froxel_integrate.comp)
// and every frame the apply: terrain and sky read the volume at their depth (froxel_apply.glsl).
#include <memory>
#include <vector>

#include "frame_context.hpp"
#include "froxel_medium.hpp"
#include "froxel_shell.hpp"
#include "froxel_tile_bounds.hpp"
#include "kiri/geometry/froxel_options.hpp"
#include "kiri/render/renderer.hpp"
#include "pass_timer.hpp"
#include "shader_program.hpp"
#include "shadow_map_pass.hpp"

namespace kiri::geometry {
class Medium;
}

namespace kiri::render::detail {

class TerrainPass;

class FroxelPass {
public:
    FroxelPass();
    ~FroxelPass();
    //! medium may be null (height fog alone); it is kept by pointer.
    void set_fog(const geometry::Medium* medium, const geometry::FroxelOptions& options);
    void clear();
    bool enabled() const { return enabled_; }
    //! Grows (lo, hi) to hold the Medium (for the frame's near and far planes).
    void extend_bounds(glm::dvec3& lo, glm::dvec3& hi) const;
    //! Runs the passes this frame needs before the scene is drawn; leaves the framebuffer unbound.
    void update(const FrameContext& frame, const TerrainPass& terrain);
    //! The apply's uniforms and textures on a program linking froxel_common.glsl and
    //! froxel_apply.glsl (and terrain_shadow.glsl when terrain_shadow).
    void bind_apply(const ShaderProgram& program, bool terrain_shadow) const;
    //! The same for a frame without froxel fog.
    static void bind_none(const ShaderProgram& program);
    //! The fog the last frame's pixels received at the terrain's depth at their centres.
    FogBuffer read_fog(const FrameContext& frame, const TerrainPass& terrain);
    const FroxelStats& stats() const { return stats_; }
    //! The timings of the passes that ran this frame (read after the frame finished).
    void append_timings(std::vector<PassTime>& out) const;

private:
    struct Volumes;
    std::unique_ptr<Volumes> v_;
    ShaderProgram density_, lighting_, temporal_, integrate_;
    std::unique_ptr<ShaderProgram> readback_, depth_program_;  // built on first use
    FroxelMedium medium_gpu_;
    FroxelTileBounds tile_bounds_;
    ShadowMapPass shadow_;
    ShellMesh shell_;
    const geometry::Medium* medium_ = nullptr;
    geometry::FroxelOptions options_;
    bool enabled_ = false, apply_ = false;
    // The frame the volume was built for, and the one before (reprojection).
    struct View {
        glm::mat4 view_projection{1.0f};
        glm::vec3 eye{0.0f}, forward{0.0f, 1.0f, 0.0f}, right{1.0f, 0.0f, 0.0f}, up{0.0f, 0.0f, 1.0f};
        float near = 1.0f, far = 2.0f;
    } view_, previous_;
    std::vector<double> key_, layout_;
    int static_frames_ = 0, frame_index_ = 0, current_ = 0;
    bool history_valid_ = false;
    FroxelStats stats_;
    std::vector<PassTimer> timers_;
    std::vector<bool> timer_ran_;

    std::vector<double> make_key(const FrameContext& frame, const TerrainPass& terrain) const;
    bool visible(const FrameContext& frame) const;
    void bind_layout(const ShaderProgram& program) const;
    void run_passes(const FrameContext& frame, const TerrainPass& terrain);
};

}  // namespace kiri::render::detail
