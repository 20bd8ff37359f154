#include "preview_app.hpp"

#include <epoxy/gl.h>
// epoxy first: GLFW then skips its own GL header.
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "camera_path.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/scene/dem_scene.hpp"
#include "kiri/geometry/terrain/terrain.hpp"
#include "kiri/render/image.hpp"
#include "kiri/render/scene_rendering.hpp"
#include "scene_file.hpp"

namespace kiri::preview {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

bool same(const render::Camera& a, const render::Camera& b)
{
    return a.position == b.position && a.target == b.target && a.fov_y_deg == b.fov_y_deg;
}

// Overlay names: the renderer draws them by their style's order.
constexpr const char* surface_overlay = "surface";
constexpr const char* triangles_overlay = "triangles";
constexpr const char* patches_overlay = "patches";
constexpr const char* control_overlay = "control";

void apply_view_args(const std::vector<std::string>& views, ViewOptions& v)
{
    for (const std::string& name : views) {
        if (name == "surface")
            v.surface = ViewOptions::Surface::shaded;
        else if (name == "deviation")
            v.surface = ViewOptions::Surface::deviation;
        else if (name == "clearance")
            v.surface = ViewOptions::Surface::clearance;
        else if (name == "triangles")
            v.tessellation = true;
        else if (name == "patches")
            v.patches = true;
        else if (name == "control")
            v.control_mesh = true;
    }
}

}  // namespace

PreviewApp::PreviewApp(const Args& args) : args_(args)
{
    // Absolute, so the terrain path resolves wherever the scene is saved to.
    scene_ = geometry::load_scene_or_dem(fs::absolute(args.scene));
    {
        // The keys the scene leaves out, derived once from its terrain (scene_defaults.hpp): the
        // panels start from them and the cameras frame the terrain. Later runs keep them.
        geometry::Pipeline terrain_only;
        scene_ = *terrain_only.run(scene_, {geometry::Stage::terrain}).scene;
    }
    if (!args.camera_path.empty())
        camera_path_ = load_camera_path(args.camera_path);
    ui_.view.fog = !args.no_fog;
    // "auto" is kiri render's default: combined (every renderer its share of the fog).
    if (args.mode == "auto")
        ui_.view.mode = render::FogMode::combined;
    else if (!render::parse_fog_mode(args.mode, ui_.view.mode) || ui_.view.mode == render::FogMode::terrain)
        throw Error("--mode: '" + args.mode + "' is not layers, particles, froxel or combined");
    ui_.view.show_panel = ui_.view.show_stats = !args.no_ui;
    ui_.view.moving_fps = args.moving_fps;
    apply_view_args(args.views, ui_.view);
    const fs::path scene_path(args.scene);
    ui_.save_path = (scene_path.parent_path() / (scene_path.stem().string() + "-edited.json")).string();
    window_ =
        render::create_window_context(args.width, args.height, "kiri preview - " + scene_path.filename().string());
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini beside the user's files
    // Ours first: ImGui's back end chains to the callback installed before it.
    glfwSetWindowUserPointer(window_->window(), this);
    glfwSetKeyCallback(window_->window(), on_key);
    glfwSetMouseButtonCallback(window_->window(), on_mouse_button);
    glfwSetCursorPosCallback(window_->window(), on_cursor);  // ImGui 1.86 polls the cursor instead
    ImGui_ImplGlfw_InitForOpenGL(window_->window(), true);
    ImGui_ImplOpenGL3_Init("#version 450 core");
    scale_ui_to_monitor();
    renderer_ = std::make_unique<render::Renderer>();
    request();
}

render::FogMode PreviewApp::drawn_mode() const
{
    const render::FogMode mode = ui_.view.mode;
    if (!ui_.view.fog)
        return render::FogMode::terrain;
    if (!scene_.fog && (mode == render::FogMode::layers || mode == render::FogMode::particles))
        return render::FogMode::terrain;
    if (!scene_.fog && !geometry::world_froxel_options(scene_).height_fog.enabled())
        return render::FogMode::terrain;
    return mode;
}

geometry::PipelineTarget PreviewApp::pipeline_target() const
{
    geometry::PipelineTarget target = render::pipeline_target(drawn_mode(), scene_);
    if (target.up_to < geometry::Stage::layer_base)
        target.up_to = geometry::Stage::layer_base;
    return target;
}

void PreviewApp::request()
{
    requested_target_ = pipeline_target();
    // The fog's time plays per frame (SceneRendering moves the Medium in time): the pipeline
    // makes it at time 0, so playing never remakes it.
    geometry::Scene at_rest = scene_;
    at_rest.medium.time = 0.0;
    pipeline_.request(at_rest, requested_target_);
}

PreviewApp::~PreviewApp()
{
    renderer_.reset();  // GL objects go while the context lives
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
}

void PreviewApp::scale_ui_to_monitor()
{
    // On HiDPI screens whose framebuffer is already larger than the window (macOS, Wayland)
    // ImGui scales up by itself; where window units are pixels (X11) the content scale has to
    // enlarge the text and widgets instead.
    float xscale = 1.0f, yscale = 1.0f;
    glfwGetWindowContentScale(window_->window(), &xscale, &yscale);
    int fb_w = 0, fb_h = 0, win_w = 0, win_h = 0;
    window_->framebuffer_size(fb_w, fb_h);
    glfwGetWindowSize(window_->window(), &win_w, &win_h);
    const float framebuffer_scale = win_w > 0 ? float(fb_w) / float(win_w) : 1.0f;
    ui_scale_ = std::clamp(xscale / std::max(framebuffer_scale, 1.0f), 1.0f, 4.0f);
    if (ui_scale_ > 1.0f) {
        ImGui::GetIO().FontGlobalScale = ui_scale_;
        ImGui::GetStyle().ScaleAllSizes(ui_scale_);
    }
}

void PreviewApp::report(const std::string& message, bool error)
{
    ui_.message = message;
    ui_.message_is_error = error;
}

void PreviewApp::apply(Products p)
{
    if (!p.error.empty())
        report(p.error, true);
    else if (ui_.message_is_error)
        report("");
    // The renderer keeps the terrain and the fog by reference: the old products go once the
    // new ones are in.
    const Products old = std::exchange(shown_, std::move(p));
    if (shown_.fog.terrain)  // uploads only when the terrain or its surround changed
        renderer_->set_terrain(*shown_.fog.terrain, 1.0, shown_.scene.terrain.surround);
    apply_live_options();
    if (shown_.views != old.views)
        update_overlays();
    scene_dirty_ = true;
    if (!camera_placed_ && shown_.fog.terrain) {
        place_camera(args_.camera);
        camera_placed_ = true;
    }
}

void PreviewApp::apply_live_options()
{
    if (!shown_.fog.terrain)
        return;
    try {
        if (rendering_)
            rendering_->update(scene_, shown_.fog, drawn_mode());
        else
            rendering_.emplace(scene_, shown_.fog, drawn_mode());
    } catch (const std::exception& e) {
        report(e.what(), true);  // the last valid rendering stays
    }
    if (rendering_)
        rendering_->apply(*renderer_);
}

void PreviewApp::update_overlays()
{
    const ViewOptions& v = ui_.view;
    const FogViews* views = shown_.views.get();
    if (!views) {
        for (const char* name : {surface_overlay, triangles_overlay, patches_overlay, control_overlay})
            renderer_->remove_overlay(name);
        uploaded_views_.reset();
        return;
    }
    const bool new_views = views != uploaded_views_.get();
    if (v.surface != ViewOptions::Surface::hidden && (new_views || v.surface != uploaded_surface_)) {
        render::OverlayMesh surface = views->surface;
        if (v.surface == ViewOptions::Surface::deviation)
            surface.colors = views->deviation_colors;
        else if (v.surface == ViewOptions::Surface::clearance)
            surface.colors = views->clearance_colors;
        renderer_->set_overlay(surface_overlay, surface);
        uploaded_surface_ = v.surface;
    }
    if (new_views) {
        render::OverlayMesh triangles = views->surface;
        triangles.normals.clear();  // lines read better unlit
        renderer_->set_overlay(triangles_overlay, triangles);
        renderer_->set_overlay(patches_overlay, views->patch_borders);
        renderer_->set_overlay(control_overlay, views->control_mesh);
        uploaded_views_ = shown_.views;
    }
    const glm::vec4 shaded =
        v.surface == ViewOptions::Surface::shaded ? glm::vec4(0.85f, 0.9f, 1.0f, 1.0f) : glm::vec4(1.0f);
    renderer_->set_overlay_style(surface_overlay,
                                 {.color = glm::vec4(glm::vec3(shaded), v.surface_opacity),
                                  .visible = v.surface != ViewOptions::Surface::hidden,
                                  .order = 0});
    renderer_->set_overlay_style(
        triangles_overlay,
        {.color = {1.0f, 1.0f, 1.0f, 0.35f}, .visible = v.tessellation, .wireframe = true, .lift = 1e-3f, .order = 1});
    renderer_->set_overlay_style(
        patches_overlay, {.color = {1.0f, 0.8f, 0.15f, 0.95f}, .visible = v.patches, .lift = 1.5e-3f, .order = 2});
    renderer_->set_overlay_style(control_overlay,
                                 {.color = {1.0f, 0.25f, 0.85f, 0.95f}, .visible = v.control_mesh, .order = 3});
}

void PreviewApp::place_camera(const std::string& name)
{
    const geometry::Bounds3 b = shown_.fog.terrain->bounds();
    const geometry::CameraSpec c = scene_.camera(name, b.min, b.max);
    camera_.look(c.position, c.target, c.fov_y_deg);
}

void PreviewApp::draw_panel()
{
    ViewOptions& view = ui_.view;
    bool edited = false, view_changed = ui_.mode_changed;
    const ViewOptions::Surface before = view.surface;
    if (view.show_panel) {
        const ImGuiIO& io = ImGui::GetIO();
        const float width = 420.0f * ui_scale_;
        ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x - width - 10.0f, 10.0f), ImGuiCond_FirstUseEver);
        ImGui::SetNextWindowSize(ImVec2(width, io.DisplaySize.y - 20.0f), ImGuiCond_FirstUseEver);
        ImGui::SetNextWindowBgAlpha(0.85f);
        ImGui::Begin("kiri");
        ImGui::PushItemWidth(ImGui::GetWindowWidth() * 0.5f);  // room for the labels
        // Stages that feed the pipeline, then what applies per frame.
        const geometry::PipelineProducts* fog = shown_.fog.has_fog() ? &shown_.fog : nullptr;
        edited |= terrain_panel(scene_);
        edited |= fog_panel(scene_, shown_.fog.terrain.get(), fog);
        edited |= placement_panel(scene_, shown_.fog.terrain.get(), fog);
        edited |= layers_panel(scene_);
        edited |= medium_panel(scene_, view);
        edited |= particles_panel(scene_, shown_.fog.particles.get(), renderer_->attenuation());
        edited |= froxel_panel(scene_, renderer_->last_stats().froxel);
        edited |= combined_panel(scene_);
        edited |= sun_panel(scene_);
        view_changed |= view_panel(view, shown_.views.get());
        camera_panel(scene_, ui_);
        file_panel(ui_);
        ImGui::PopItemWidth();
        ImGui::End();
    }
    // Stages whose inputs did not change are kept; a new mode may need the medium or particles.
    if (edited || pipeline_target() != requested_target_)
        request();
    if (edited || view_changed) {
        apply_live_options();
        if (view_changed || view.surface != before)
            update_overlays();
        scene_dirty_ = true;
    }
    if (view.show_stats) {
        const render::AttenuationBuffer& buffer = renderer_->attenuation();
        const geometry::ParticleCloud* cloud = rendering_ ? rendering_->particles() : nullptr;
        const FogCounts counts{froxels_on(), cloud ? cloud->particles.size() : 0, buffer.rebuild_count(),
                               buffer.last_build_ms()};
        stats_overlay(times_, renderer_->last_stats(), counts, pipeline_.status());
    }
}

void PreviewApp::do_actions()
{
    if (ui_.bookmark >= 0 && shown_.fog.terrain)
        place_camera(scene_.cameras.at(std::size_t(ui_.bookmark)).name);
    if (ui_.reset_camera && shown_.fog.terrain)
        place_camera(args_.camera);
    if (ui_.focus_fog)
        focus_fog();
    if (ui_.add_camera)
        add_camera();
}

void PreviewApp::focus_fog()
{
    if (!shown_.fog.has_fog()) {
        report("no fog to focus on");
        return;
    }
    // The fitted surface's bounds (the layer base less its offset).
    const glm::dvec3 offset(0.0, 0.0, shown_.fog.layers.base_offset);
    const glm::dvec3 lo = shown_.fog.layer_base->min - offset, hi = shown_.fog.layer_base->max - offset;
    const glm::dvec3 centre = 0.5 * (lo + hi);
    const double radius = 0.5 * glm::length(hi - lo);
    const render::Camera c = camera_.camera();
    const glm::dvec3 direction = glm::normalize(c.target - c.position);
    const double distance = radius / std::tan(c.fov_y_deg * M_PI / 360.0);
    camera_.look(centre - distance * direction, centre, c.fov_y_deg);
}

void PreviewApp::add_camera()
{
    const std::string base = ui_.new_camera_name.empty() ? "view" : ui_.new_camera_name;
    std::string name = base;
    const auto taken = [&](const std::string& n) {
        return std::any_of(scene_.cameras.begin(), scene_.cameras.end(), [&](const auto& c) { return c.name == n; });
    };
    for (int n = 2; taken(name); ++n)
        name = base + "-" + std::to_string(n);
    const render::Camera c = camera_.camera();
    scene_.cameras.push_back({name, c.position, c.target, c.fov_y_deg});
    report("camera '" + name + "' added to the scene (saved with it)");
}

bool PreviewApp::draw_scene(int fb_w, int fb_h, bool camera_moved, bool force)
{
    if (!shown_.fog.terrain) {  // the first job is still running
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, fb_w, fb_h);
        glClearColor(0.12f, 0.13f, 0.15f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        return false;
    }
    const ViewOptions& v = ui_.view;
    float scale = v.render_scale;
    const FrameBudget budget{1000.0 / std::clamp(double(v.moving_fps), 0.1, 1000.0), 0.125f, v.render_scale};
    // Dragging a slider redraws every frame too: reduced as well, so the panel keeps up.
    const float moving_scale =
        std::clamp(moving_scale_, budget.min_scale, std::max(budget.min_scale, budget.max_scale));
    const bool reduced =
        (camera_moved || ImGui::IsAnyItemActive()) && !force && v.reduce_while_moving && moving_scale < scale;
    if (reduced)
        scale = moving_scale;
    int w = std::max(1, int(std::lround(fb_w * scale))), h = std::max(1, int(std::lround(fb_h * scale)));
    if (reduced) {  // a size llvmpipe has compiled the passes for (frame_budget.hpp)
        w = std::min(off_power_of_two(w), std::max(fb_w, 1));
        h = std::min(off_power_of_two(h), std::max(fb_h, 1));
    }
    const bool redraw = force || scene_dirty_ || camera_moved || w != last_width_ || h != last_height_ ||
        (last_frame_reduced_ && !reduced);
    if (redraw) {
        last_camera_ = camera_.camera();
        const double step = reduced ? resolution_step(scale / v.render_scale) : 1.0;
        renderer_->set_froxel_resolution(step);
        renderer_->set_terrain_resolution(step);
        renderer_->set_particle_resolution(step);
        renderer_->draw(last_camera_, w, h);
        times_.scene_ms = renderer_->last_stats().frame_ms;
        // The next moving frame's scale follows this one's cost; a still's says nothing of it.
        if ((camera_moved || ImGui::IsAnyItemActive()) && v.reduce_while_moving && !force)
            moving_scale_ = next_moving_scale(scale, times_.scene_ms, budget);
        times_.scene_width = last_width_ = w;
        times_.scene_height = last_height_ = h;
        ++times_.scene_frames;
        // A moving view's froxels refine once the view holds (one more frame, a still); then
        // nothing reruns, and the view is not redrawn.
        const render::FroxelStats& froxel = renderer_->last_stats().froxel;
        scene_dirty_ = froxel.visible && !froxel.converged;
        last_frame_reduced_ = reduced;
    } else {
        ++times_.reused_frames;
    }
    renderer_->present(fb_w, fb_h);
    return redraw;
}

bool PreviewApp::view_settled() const
{
    const PipelineStatus s = pipeline_.status();
    if (s.busy || s.waiting || s.finished != s.requested)
        return false;
    // A scene that never loaded has nothing more to show; playing time keeps the froxels moving.
    return !shown_.fog.terrain || (!last_frame_reduced_ && (!scene_dirty_ || ui_.view.play_time));
}

void PreviewApp::screenshot(const fs::path& path)
{
    render::write_png_atomic(path, window_->read_back_buffer());
    std::printf("%s\n", path.string().c_str());
    std::fflush(stdout);
    report("wrote " + path.string());
}

int PreviewApp::run()
{
    if (args_.scripted()) {  // the picture shows the finished scene
        pipeline_.wait_idle();
        if (auto p = pipeline_.take())
            apply(std::move(*p));
        if (!shown_.fog.terrain || ui_.message_is_error)
            throw Error(ui_.message.empty() ? "the scene could not be prepared" : ui_.message);
    }
    int frame = 0;
    std::vector<double> scene_ms;
    // Per drawn frame (scripted): attenuation builds, froxel passes run, the 3D view's size.
    std::string rebuilds, froxel_runs, sizes;
    auto last = Clock::now();
    while (!window_->should_close()) {
        const auto start = Clock::now();
        // A long wait for events is not a long step of flight.
        const double seconds = std::min(std::chrono::duration<double>(start - last).count(), 0.1);
        last = start;
        if (auto p = pipeline_.take())
            apply(std::move(*p));
        int fb_w = 0, fb_h = 0;
        window_->framebuffer_size(fb_w, fb_h);
        if (fb_w <= 0 || fb_h <= 0) {  // minimised: nothing to draw
            glfwWaitEventsTimeout(0.1);
            continue;
        }
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        ui_.clear_actions();
        handle_input(seconds);
        if (ui_.view.play_time) {  // wind and dissipation run in real time
            scene_.medium.time += seconds;
            apply_live_options();
            scene_dirty_ = true;
        }
        if (!camera_path_.empty()) {
            const render::Camera c =
                camera_on_path(camera_path_, args_.frames > 1 ? double(frame) / (args_.frames - 1) : 0.0);
            camera_.look(c.position, c.target, c.fov_y_deg);
        }
        draw_panel();
        ImGui::Render();
        do_actions();
        const bool moved = !same(camera_.camera(), last_camera_);
        // Scripted with --moving: the camera path's frames are drawn as an interactive session
        // draws a moving view, the last one as the still it refines to.
        const bool still = args_.scripted() && (!args_.moving || frame + 1 >= args_.frames);
        if (draw_scene(fb_w, fb_h, moved, still) && args_.scripted()) {
            scene_ms.push_back(times_.scene_ms);
            sizes += ' ';
            sizes += std::to_string(times_.scene_width) + "x" + std::to_string(times_.scene_height);
            rebuilds += ' ';  // (" " + to_string trips GCC 12's -Wrestrict false positive)
            rebuilds += std::to_string(renderer_->last_stats().attenuation_rebuilds);
            froxel_runs += renderer_->last_stats().froxel.updated ? " 1" : " 0";
        }
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        try {
            screenshot_pending_ |= ui_.screenshot;
            if (screenshot_pending_ && view_settled()) {
                screenshot_pending_ = false;
                screenshot(next_screenshot_path(fs::current_path(), fs::path(args_.scene).stem().string()));
            }
            if (ui_.save) {
                save_scene(scene_, ui_.save_path);
                report("saved " + ui_.save_path);
            }
        } catch (const std::exception& e) {
            report(e.what(), true);
        }
        if (args_.scripted() && ++frame >= args_.frames) {
            screenshot(args_.screenshot);
            if (!args_.save.empty())
                save_scene(scene_, args_.save);
            if (!scene_ms.empty()) {
                const auto [lo, hi] = std::minmax_element(scene_ms.begin(), scene_ms.end());
                double sum = 0.0;
                for (double ms : scene_ms)
                    sum += ms;
                std::fprintf(stderr, "kiri-preview: %d frames of %dx%d, 3D view %.1f ms mean (%.1f..%.1f)\n", frame,
                             times_.scene_width, times_.scene_height, sum / double(scene_ms.size()), *lo, *hi);
            }
            if (args_.moving) {
                std::fprintf(stderr, "kiri-preview: 3D view size per frame:%s\n", sizes.c_str());
                std::fprintf(stderr, "kiri-preview: 3D view time per frame (ms):");
                for (double ms : scene_ms)
                    std::fprintf(stderr, " %.0f", ms);
                std::fprintf(stderr, "\n");
            }
            if (const geometry::ParticleCloud* cloud = rendering_ ? rendering_->particles() : nullptr)
                std::fprintf(stderr, "kiri-preview: %zu particles, attenuation buffer builds per frame:%s\n",
                             cloud->particles.size(), rebuilds.c_str());
            if (froxels_on())
                std::fprintf(stderr, "kiri-preview: froxel passes run per frame:%s\n", froxel_runs.c_str());
            // Where the last frame (with --moving, the still) went, as kiri render --timings
            // prints a still's passes.
            std::string passes;
            for (const render::PassTime& t : renderer_->last_stats().passes) {
                char entry[96];
                std::snprintf(entry, sizeof entry, " %s %.0f,", t.pass.c_str(), t.gpu_ms);
                passes += entry;
            }
            if (!passes.empty()) {
                passes.pop_back();
                std::fprintf(stderr, "kiri-preview: the last frame's passes (ms):%s\n", passes.c_str());
            }
            return 0;
        }
        window_->swap_buffers();
        times_.loop_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
        // Idle: sleep until an event (or a moment, to show the pipeline's progress).
        const ImGuiIO& io = ImGui::GetIO();
        const bool active = moved || scene_dirty_ || screenshot_pending_ || ui_.view.play_time ||
            ImGui::IsAnyItemActive() || io.MouseDown[0] || io.MouseDown[1] || io.MouseDown[2] ||
            io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f || io.MouseWheel != 0.0f;
        if (args_.scripted() || active)
            glfwPollEvents();
        else
            glfwWaitEventsTimeout(pipeline_.status().busy ? 0.1 : 0.5);
    }
    // What the session cost the renderer: a static view adds 3D frames neither here nor there.
    std::fprintf(stderr, "kiri-preview: 3D frames drawn %lld, shown again %lld; attenuation buffer builds %d\n",
                 times_.scene_frames, times_.reused_frames, renderer_->attenuation().rebuild_count());
    return 0;
}

}  // namespace kiri::preview
