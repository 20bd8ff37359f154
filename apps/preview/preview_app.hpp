#pragma once
// The preview window: a GLFW window with the 3D view and the Dear ImGui panel. The loop reads
// input, runs the panels (which edit the scene), hands the scene to the pipeline when it
// changed, applies what the pipeline finished, draws the 3D view only when something in it
// changed (otherwise the last frame is shown again), then the panel on top.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "kiri/geometry/scene/scene.hpp"
#include "kiri/render/renderer.hpp"
#include "kiri/render/scene_rendering.hpp"
#include "kiri/render/window_context.hpp"
#include "frame_budget.hpp"
#include "mouse_drags.hpp"
#include "orbit_camera.hpp"
#include "panels/panels.hpp"
#include "pipeline.hpp"

namespace kiri::preview {

struct Args {
    std::string scene, camera, screenshot, save, camera_path, mode = "auto";
    std::vector<std::string> views;  //!< surface, deviation, clearance, triangles, patches, control
    int frames = 0, width = 1280, height = 720;
    bool no_fog = false, no_ui = false;
    bool moving = false;       //!< scripted: draw the camera path's frames as a moving view
    float moving_fps = 10.0f;  //!< the moving view's frame budget (ViewOptions::moving_fps)
    bool scripted() const { return frames > 0; }
};

class PreviewApp {
public:
    //! \throw kiri::Error (no display, no OpenGL 4.5), InputError (the scene).
    explicit PreviewApp(const Args& args);
    ~PreviewApp();
    //! The window loop; returns the exit code. In scripted mode: --frames frames, then the
    //! screenshot and the saved scene. \throw kiri::Error when the scene cannot be shown.
    int run();

private:
    Args args_;
    geometry::Scene scene_;
    std::unique_ptr<render::WindowContext> window_;
    std::unique_ptr<render::Renderer> renderer_;
    Pipeline pipeline_;
    // What the window shows, from the last finished job, and how the renderer draws it.
    Products shown_;
    std::optional<render::SceneRendering> rendering_;
    std::shared_ptr<const FogViews> uploaded_views_;
    geometry::PipelineTarget requested_target_;  // what the last request asked the pipeline for
    ViewOptions::Surface uploaded_surface_ = ViewOptions::Surface::hidden;
    OrbitCamera camera_;
    bool camera_placed_ = false;
    std::vector<render::Camera> camera_path_;
    UiState ui_;
    FrameTimes times_;
    // The 3D frame on screen and what it showed, to draw again only on a change.
    bool scene_dirty_ = true, last_frame_reduced_ = false;
    render::Camera last_camera_;
    int last_width_ = 0, last_height_ = 0;
    float moving_scale_ = 0.5f;  // the next moving frame's scale (frame_budget.hpp)

    float ui_scale_ = 1.0f;
    //! Queues the scene with what the render mode needs.
    void request();
    //! The mode drawn: the view's, or the terrain alone when the fog is hidden or the scene has
    //! nothing of it to draw.
    render::FogMode drawn_mode() const;
    //! What the pipeline makes for the view: the fog's surface and layers always (the views of
    //! the surface need them), and what the render mode draws.
    geometry::PipelineTarget pipeline_target() const;
    bool froxels_on() const { return rendering_ && rendering_->draws_froxels(); }
    void scale_ui_to_monitor();
    void apply(Products products);
    //! The rendering of the current scene and products, applied to the renderer.
    void apply_live_options();
    void update_overlays();
    bool handle_input(double seconds);  // true while the camera moves
    void handle_keys();
    void handle_key(int key, int mods);
    //! Keys pressed since the last frame: a press and release within one slow frame (llvmpipe)
    //! still counts, which ImGui 1.86's key state alone would miss.
    struct KeyPress {
        int key, mods;
    };
    std::vector<KeyPress> key_presses_;
    static void on_key(GLFWwindow* window, int key, int scancode, int action, int mods);
    MouseDrags drags_;
    static void on_mouse_button(GLFWwindow* window, int button, int action, int mods);
    static void on_cursor(GLFWwindow* window, double x, double y);
    void place_camera(const std::string& name);
    void focus_fog();
    void pivot_at_cursor();
    void add_camera();
    void do_actions();
    //! Draws the 3D view if needed and copies it to the window; returns whether it drew.
    bool draw_scene(int framebuffer_width, int framebuffer_height, bool camera_moved, bool force);
    void draw_panel();
    void screenshot(const std::filesystem::path& path);
    //! F12 waits for the view it was pressed on to settle: the pipeline's newest products shown,
    //! the frame drawn at full scale and its froxels converged, so that the picture is the one
    //! the view settles to, not a reduced moving frame or the fog of the edit before.
    bool screenshot_pending_ = false;
    bool view_settled() const;
    void report(const std::string& message, bool error = false);
};

}  // namespace kiri::preview
