// kiri-preview SCENE.json: the interactive preview (docs/preview.md). A GLFW window with a
// parameter panel; edits are recomputed off the render thread; `--frames N --screenshot OUT`
// renders N frames and writes a PNG (scripted mode, for tests and documentation).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "kiri/geometry/error.hpp"
#include "kiri/geometry/fog_target.hpp"
#include "kiri/render/image.hpp"
#include "kiri/render/renderer.hpp"
#include "kiri/render/window_context.hpp"
#include "orbit_camera.hpp"
#include "panel.hpp"
#include "scene_worker.hpp"

namespace {

using namespace kiri;
using namespace kiri::preview;

struct Args {
    std::string scene, screenshot, camera;
    int frames = 0, width = 1280, height = 720;
    bool no_fog = false, wireframe = false, deviation = false;
};

render::SunLight to_sun(const geometry::SunSpec& s) { return {s.direction, s.color, s.intensity, s.ambient}; }

class Preview {
public:
    explicit Preview(const Args& args) : args_(args)
    {
        scene_ = geometry::load_scene(args.scene);
        window_ = render::create_window_context(args.width, args.height, "kiri preview - " + args.scene);
        IMGUI_CHECKVERSION();
        ImGui::CreateContext();
        ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
        ImGui_ImplGlfw_InitForOpenGL(window_->window(), true);
        ImGui_ImplOpenGL3_Init("#version 450 core");
        renderer_ = std::make_unique<render::Renderer>();
        panel_.show_fog = !args.no_fog;
        panel_.control_wireframe = panel_.patch_wireframe = args.wireframe;
        panel_.deviation_map = args.deviation;
        worker_.request(scene_, state_);
    }
    ~Preview()
    {
        worker_.wait();
        renderer_.reset();
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }

    int run()
    {
        if (scripted()) {  // the picture must show the finished scene
            apply(worker_.wait());
            if (!state_.error.empty())
                throw Error(state_.error);
        }
        int frame = 0;
        auto last = std::chrono::steady_clock::now();
        while (!window_->should_close()) {
            glfwPollEvents();
            apply(worker_.poll());
            const auto now = std::chrono::steady_clock::now();
            const double seconds = std::chrono::duration<double>(now - last).count();
            last = now;
            int fb_w = 0, fb_h = 0;
            window_->framebuffer_size(fb_w, fb_h);
            if (fb_w == 0 || fb_h == 0) {  // minimised: nothing to draw
                glfwWaitEventsTimeout(0.1);
                continue;
            }
            handle_input(seconds, fb_h);
            update_wireframes();
            if (state_.terrain) {
                renderer_->draw(camera_.camera(), fb_w, fb_h);
                renderer_->present(fb_w, fb_h);
            }
            draw_ui(seconds * 1e3);
            // Screenshots of the window as the user sees it, panel included.
            if (panel_.screenshot_requested || screenshot_key())
                screenshot(next_screenshot_name());
            if (scripted() && ++frame >= args_.frames) {
                screenshot(args_.screenshot);
                return 0;
            }
            window_->swap_buffers();
            if (panel_.save_requested)
                save();
        }
        return 0;
    }

private:
    Args args_;
    geometry::Scene scene_;
    std::unique_ptr<render::WindowContext> window_;
    std::unique_ptr<render::Renderer> renderer_;
    SceneWorker worker_;
    SceneState state_;
    OrbitCamera camera_;
    PanelState panel_;
    WorkStatus work_;
    bool camera_placed_ = false, p_was_down_ = false;
    // What the wireframes were built from, to rebuild them only when it changes.
    const void* wire_fog_ = nullptr;
    bool wire_control_ = false, wire_patches_ = false, wire_deviation_ = false;

    // The fit's deviation from its target per tessellation vertex, blue (below) to red (above).
    void update_deviation_map()
    {
        std::vector<glm::dvec3> positions;
        std::vector<glm::vec4> colors;
        std::vector<unsigned> triangles;
        if (state_.fog && wire_deviation_) {
            const geometry::TriMesh& m = state_.fog->authored.tessellation.mesh;
            const geometry::FogSpec spec = geometry::world_fog_spec(state_.scene);
            const geometry::Heightfield& hf = state_.terrain->heightfield();
            const geometry::Heightfield smooth = geometry::smooth_heightfield(hf, spec.fit.smoothing_length);
            std::vector<double> deviation;
            double scale = 1e-9;
            for (auto v : m.vertices()) {
                const auto& p = m.point(v);
                double target = spec.fit.altitude;
                if (spec.fit.mode == geometry::FitMode::blanket)
                    target = std::max(geometry::sample_bilinear(smooth, p[0], p[1]) + spec.fit.offset,
                                      state_.terrain->height(p[0], p[1]) + spec.fit.clearance);
                deviation.push_back(p[2] - target);
                scale = std::max(scale, std::abs(deviation.back()));
                positions.push_back({p[0], p[1], p[2]});
            }
            for (double d : deviation) {
                const float t = float(std::clamp(d / scale, -1.0, 1.0));
                colors.push_back(t < 0.0f ? glm::vec4(1.0f + t, 1.0f + t, 1.0f, 0.7f) : glm::vec4(1.0f, 1.0f - t, 1.0f - t, 0.7f));
            }
            for (auto f : m.faces())
                for (auto v : m.fv_range(f))
                    triangles.push_back(unsigned(v.idx()));
            panel_.deviation_scale = scale;
        }
        renderer_->set_overlay_mesh(positions, colors, triangles);
    }

    void update_wireframes()
    {
        const void* fog = state_.fog.get();
        if (fog == wire_fog_ && wire_control_ == panel_.control_wireframe && wire_patches_ == panel_.patch_wireframe &&
            wire_deviation_ == panel_.deviation_map)
            return;
        wire_fog_ = fog;
        wire_deviation_ = panel_.deviation_map;
        update_deviation_map();
        wire_control_ = panel_.control_wireframe;
        wire_patches_ = panel_.patch_wireframe;
        std::vector<glm::dvec3> control, patches;
        if (state_.fog && wire_control_) {
            const geometry::BaseSurface& s = state_.fog->authored.surface;
            const geometry::PolyMesh& m = s.control().mesh;
            const std::vector<double> z = s.heights();
            for (auto e : m.edges()) {
                for (auto v : {m.from_vertex_handle(m.halfedge_handle(e, 0)), m.to_vertex_handle(m.halfedge_handle(e, 0))}) {
                    const auto& p = m.point(v);
                    control.push_back({p[0], p[1], z[std::size_t(v.idx())]});
                }
            }
        }
        if (state_.fog && wire_patches_) {
            const geometry::BaseSurface& s = state_.fog->authored.surface;
            const int steps = 12;
            for (int f = 0; f < s.num_patches(); ++f)
                for (int side = 0; side < 4; ++side)
                    for (int k = 0; k < steps; ++k)
                        for (int end = 0; end < 2; ++end) {
                            const double t = double(k + end) / steps;
                            const double u = side == 0 ? t : side == 1 ? 1.0 : side == 2 ? 1.0 - t : 0.0;
                            const double v = side == 0 ? 0.0 : side == 1 ? t : side == 2 ? 1.0 : 1.0 - t;
                            patches.push_back(s.evaluate(f, u, v));
                        }
        }
        renderer_->set_lines(0, control, {1.0f, 0.55f, 0.1f, 1.0f});
        renderer_->set_lines(1, patches, {0.1f, 0.85f, 1.0f, 1.0f});
    }
    int screenshots_ = 0;

    bool scripted() const { return args_.frames > 0 && !args_.screenshot.empty(); }

    void apply(std::optional<SceneState> s)
    {
        if (!s)
            return;
        if (!s->error.empty())
            panel_.message = s->error;
        work_.terrain_rebuilds += s->terrain_rebuilt;
        work_.fog_rebuilds += s->fog_rebuilt;
        if (s->terrain_rebuilt)
            work_.terrain_seconds = s->terrain_seconds;
        if (s->fog_rebuilt)
            work_.fog_seconds = s->fog_seconds;
        state_ = std::move(*s);
        renderer_->set_terrain(*state_.terrain);
        if (!camera_placed_) {
            reset_camera(args_.camera);
            camera_placed_ = true;
        }
    }

    void reset_camera(const std::string& name)
    {
        const geometry::Bounds3 b = state_.terrain->bounds();
        const geometry::CameraSpec c = scene_.camera(name, b.min, b.max);
        camera_.look(c.position, c.target, c.fov_y_deg);
    }

    void focus_fog()
    {
        if (!state_.fog)
            return;
        const geometry::LayerBase& base = state_.fog->base;
        const glm::dvec3 centre = 0.5 * (base.min + base.max);
        const double radius = 0.5 * glm::length(base.max - base.min);
        camera_.look(centre + radius * glm::dvec3(-0.6, -1.2, 0.8), centre, 45.0);
    }

    // Applies what changes per frame (sun, layer options) and queues what needs a rebuild.
    void push_scene(bool rebuild)
    {
        renderer_->set_sun(to_sun(scene_.sun));
        renderer_->set_layer_resolution(panel_.layer_resolution);
        if (state_.fog && panel_.show_fog) {
            try {
                geometry::LayerOptions o = geometry::world_layer_options(scene_);
                o.base_offset = state_.fog->layers.base_offset;
                o.count = state_.fog->layers.count;
                renderer_->set_layers(state_.fog->base, o);
            } catch (const std::exception& e) {
                panel_.message = e.what();
            }
        } else {
            renderer_->clear_layers();
        }
        if (rebuild)
            worker_.request(scene_, state_);
    }

    void handle_input(double seconds, int fb_h)
    {
        const ImGuiIO& io = ImGui::GetIO();
        if (!io.WantCaptureMouse) {
            if (io.MouseDown[0])
                camera_.orbit(io.MouseDelta.x, io.MouseDelta.y);
            if (io.MouseDown[1])
                camera_.pan(io.MouseDelta.x, io.MouseDelta.y, fb_h);
            if (io.MouseWheel != 0.0f)
                camera_.zoom(io.MouseWheel);
        }
        if (io.WantCaptureKeyboard)
            return;
        GLFWwindow* w = window_->window();
        auto key = [w](int k) { return glfwGetKey(w, k) == GLFW_PRESS ? 1.0 : 0.0; };
        camera_.fly(key(GLFW_KEY_W) - key(GLFW_KEY_S), key(GLFW_KEY_D) - key(GLFW_KEY_A),
                    key(GLFW_KEY_E) - key(GLFW_KEY_Q), seconds);
        if (key(GLFW_KEY_R) > 0.0 && state_.terrain)
            reset_camera(args_.camera);
        if (key(GLFW_KEY_F) > 0.0)
            focus_fog();
    }

    bool screenshot_key()
    {
        const bool down = !ImGui::GetIO().WantCaptureKeyboard && glfwGetKey(window_->window(), GLFW_KEY_P) == GLFW_PRESS;
        const bool pressed = down && !p_was_down_;
        p_was_down_ = down;
        return pressed;
    }

    void draw_ui(double frame_ms)
    {
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        ImGui::SetNextWindowPos(ImVec2(ImGui::GetIO().DisplaySize.x - 390.0f, 10.0f), ImGuiCond_FirstUseEver);
        ImGui::SetNextWindowSize(ImVec2(380.0f, 0.0f), ImGuiCond_FirstUseEver);
        ImGui::Begin("kiri");
        const bool rebuild = terrain_section(scene_) | fog_section(scene_);
        const bool live = sun_section(scene_) | layers_section(scene_, panel_);
        view_section(scene_, panel_);
        ImGui::End();
        work_.busy = worker_.busy();
        work_.running_seconds = worker_.running_seconds();
        overlay(renderer_->last_stats(), work_, frame_ms);
        ImGui::Render();
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        // The texture options shape the layer base: a rebuild; the rest applies at once.
        push_scene(rebuild || (live && scene_.layers.texture.fade_width != state_.scene.layers.texture.fade_width) ||
                   scene_.layers.count != state_.scene.layers.count);
        if (panel_.bookmark >= 0 && state_.terrain) {
            reset_camera(scene_.cameras[std::size_t(panel_.bookmark)].name);
            panel_.bookmark = -1;
        }
        if (panel_.reset_camera && state_.terrain)
            reset_camera(args_.camera);
        if (panel_.focus_fog)
            focus_fog();
    }

    std::string next_screenshot_name()
    {
        const std::filesystem::path p(args_.scene);
        return p.stem().string() + "-preview-" + std::to_string(++screenshots_) + ".png";
    }

    void screenshot(const std::string& path)
    {
        render::write_png_atomic(path, window_->read_back_buffer());
        panel_.message = "wrote " + path;
        std::printf("%s\n", path.c_str());
    }

    void save()
    {
        const std::filesystem::path p(args_.scene);
        const std::filesystem::path out = p.parent_path() / (p.stem().string() + "-edited.json");
        const std::filesystem::path tmp = out.string() + ".tmp.json";
        {
            std::ofstream file(tmp, std::ios::binary);
            file << geometry::scene_to_json(scene_);
            if (!file)
                throw IoError(tmp.string(), "", "cannot write");
        }
        std::filesystem::rename(tmp, out);
        panel_.message = "saved " + out.string();
    }
};

}  // namespace

int main(int argc, char** argv)
{
    CLI::App app{"kiri-preview: interactive preview of a kiri scene"};
    Args args;
    app.add_option("scene", args.scene, "scene file (JSON)")->required();
    app.add_option("--width", args.width, "window width")->check(CLI::Range(64, 16384));
    app.add_option("--height", args.height, "window height")->check(CLI::Range(64, 16384));
    app.add_option("--camera", args.camera, "scene camera to start from (default: its first)");
    app.add_option("--frames", args.frames, "scripted mode: frames to render before the screenshot")->check(CLI::Range(1, 100000));
    app.add_option("--screenshot", args.screenshot, "scripted mode: PNG written after --frames frames");
    app.add_flag("--no-fog", args.no_fog, "start with the fog hidden");
    app.add_flag("--wireframe", args.wireframe, "start with the control mesh and patch boundaries shown");
    app.add_flag("--deviation", args.deviation, "start with the fit's deviation map shown");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0)
            return app.exit(e);
        std::fprintf(stderr, "kiri-preview: %s\n", e.what());
        return 2;
    }
    if ((args.frames > 0) != !args.screenshot.empty()) {
        std::fprintf(stderr, "kiri-preview: --frames and --screenshot go together\n");
        return 2;
    }
    try {
        Preview preview(args);
        return preview.run();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "kiri-preview: %s\n", e.what());
        return 2;
    }
}
