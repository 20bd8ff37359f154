#pragma once
// The preview's panel (Dear ImGui), one file per stage so a new stage brings its own: each
// panel edits the scene in place and returns true when it changed something; the window then
// queues the scene for recomputation (the pipeline redoes only the stages whose inputs
// changed) and applies the per-frame values (sun, layer look) at once.
#include <string>

#include "kiri/geometry/scene/scene.hpp"
#include "kiri/render/renderer.hpp"
#include "kiri/render/scene_rendering.hpp"
#include "pipeline.hpp"

namespace kiri::preview {

//! What is drawn (not part of the scene).
struct ViewOptions {
    enum class Surface { hidden, shaded, deviation, clearance };
    bool fog = true;  //!< the fog, drawn as `mode` says
    //! How the fog is drawn (render/scene_rendering.hpp): its layer stack, particles lit through
    //! the attenuation buffer, froxel volumetric fog, or all of them together (not terrain).
    render::FogMode mode = render::FogMode::layers;
    Surface surface = Surface::hidden;  //!< the fitted base surface as a translucent mesh
    float surface_opacity = 0.6f;
    bool tessellation = false;  //!< the surface's triangles as lines
    bool patches = false;       //!< patch borders
    bool control_mesh = false;
    bool play_time = false;     //!< advance the medium's time (wind, dissipation) in real time
    float render_scale = 1.0f;  //!< of the window's framebuffer
    //! While the camera moves (or a slider is dragged), draw at the scale that keeps the frame
    //! within 1 / moving_fps (frame_budget.hpp); the still view is drawn at render_scale.
    bool reduce_while_moving = true;
    float moving_fps = 10.0f;
    bool show_panel = true, show_stats = true;
};

//! The render modes the view cycles through (M), in order.
render::FogMode next_fog_mode(render::FogMode mode);

//! What the user asked for this frame (buttons and keys), and text fields that persist.
struct UiState {
    ViewOptions view;
    bool fly_mode = false;
    bool save = false, screenshot = false, reset_camera = false, focus_fog = false, add_camera = false;
    bool mode_changed = false;  //!< by a key (the panel reports its own edits)
    int bookmark = -1;
    std::string save_path, new_camera_name = "view";
    std::string message;  //!< last error or file written, at the bottom of the panel
    bool message_is_error = false;
    void clear_actions()
    {
        save = screenshot = reset_camera = focus_fog = add_camera = mode_changed = false;
        bookmark = -1;
    }
};

//! Frame times measured by the window (the renderer's own are in its FrameStats).
struct FrameTimes {
    double loop_ms = 0.0;   //!< the last iteration of the window loop (UI included)
    double scene_ms = 0.0;  //!< the last 3D frame (Renderer::draw)
    int scene_width = 0, scene_height = 0;
    long long scene_frames = 0, reused_frames = 0;  //!< drawn, and shown again unchanged
};

bool terrain_panel(geometry::Scene& scene);
bool fog_panel(geometry::Scene& scene, const geometry::Terrain* terrain, const geometry::PipelineProducts* fog);
bool sun_panel(geometry::Scene& scene);
//! The scene's "combined" section and its quality preset (every renderer's budget at once).
bool combined_panel(geometry::Scene& scene);
bool layers_panel(geometry::Scene& scene);
//! The medium's optics and its motion (detail noise, wind, time, dissipation); `view` holds
//! whether its time plays.
bool medium_panel(geometry::Scene& scene, ViewOptions& view);
//! Fog placed by the terrain (the fog section's fill, outline, flow and burn_off keys), with
//! the last placement's figures; only for a scene whose fog has them.
bool placement_panel(geometry::Scene& scene, const geometry::Terrain* terrain, const geometry::PipelineProducts* fog);
//! The scene's "particles" section: sampling (the pipeline resamples) and the attenuation
//! buffer and billboards (applied on the next frame); figures of the cloud and the buffer.
//! The scene's "froxel" section: the grid, slicing, filtering, shadows, height fog (all applied
//! on the next frame), and what the froxel passes did.
bool froxel_panel(geometry::Scene& scene, const render::FroxelStats& stats);
bool particles_panel(geometry::Scene& scene, const geometry::ParticleCloud* cloud,
                     const render::AttenuationBuffer& buffer);
//! Returns true when the picture changes (views, resolution).
bool view_panel(ViewOptions& view, const FogViews* views);
void camera_panel(const geometry::Scene& scene, UiState& ui);
void file_panel(UiState& ui);
struct FogCounts {
    bool froxels = false;               //!< froxel fog on the renderer
    std::size_t particles = 0;          //!< in the cloud on the renderer (0: none)
    int attenuation_builds = 0;         //!< since the start
    double attenuation_build_ms = 0.0;  //!< the last build
};
void stats_overlay(const FrameTimes& times, const render::FrameStats& stats, const FogCounts& fog,
                   const PipelineStatus& pipeline);

}  // namespace kiri::preview
