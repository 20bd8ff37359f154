// `kiri render SCENE.json -o OUT.png`: renders a scene headless (EGL) and writes the PNG
// atomically. The output folder is checked before any loading or rendering.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "commands.hpp"
#include "kiri/geometry/reference/reference_fog.hpp"
#include "kiri/geometry/scene/pipeline.hpp"
#include "kiri/render/gl_context.hpp"
#include "kiri/render/renderer.hpp"
#include "kiri/render/scene_rendering.hpp"
#include "kiri/render/tone_map.hpp"

namespace kiri::cli {
namespace {

struct RenderArgs {
    std::string scene, out, camera, mode = "auto";
    int width = 0, height = 0;
    bool timings = false;
};

void render_reference(const geometry::Scene& scene, const geometry::PipelineProducts& products,
                      const render::Camera& camera, int width, int height, const std::string& out)
{
    const geometry::Terrain& terrain = *products.terrain;
    const geometry::FroxelOptions options = render::scene_froxel_options(scene, terrain);
    const geometry::Medium* medium = products.medium.get();
    const geometry::ReferenceView view = render::reference_view(camera, width, height, options.far);
    const geometry::FogLighting light = render::scene_fog_lighting(scene, medium, options);
    const geometry::ReferenceImage r =
        geometry::render_reference_fog({medium, options.height_fog}, &terrain.heightfield(), view, light);
    render::write_png_atomic(out, render::tone_mapped(r));
}

void run(const RenderArgs& a)
{
    const auto start = std::chrono::steady_clock::now();
    check_output_file(a.out);
    const geometry::Scene scene = geometry::load_scene(a.scene);
    const bool reference = a.mode == "reference";  // the CPU judge: slow, no GL
    render::FogMode mode = render::default_mode(scene);
    if (reference)
        mode = render::FogMode::froxel;  // the reference draws the Medium and the height fog
    else if (a.mode != "auto")
        render::parse_fog_mode(a.mode, mode);  // CLI11 checked the name
    const geometry::PipelineProducts products = geometry::author_scene(scene, render::pipeline_target(mode, scene));
    const geometry::Bounds3 bounds = products.terrain->bounds();
    const render::Camera camera = render::to_camera(scene.camera(a.camera, bounds.min, bounds.max));
    const int width = a.width > 0 ? a.width : scene.image.width;
    const int height = a.height > 0 ? a.height : scene.image.height;

    if (reference) {
        render_reference(scene, products, camera, width, height, a.out);
        std::printf("%s\n", a.out.c_str());
        std::fprintf(stderr, "kiri render: %dx%d, mode reference, %.2f s\n", width, height,
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        return;
    }
    const render::SceneRendering rendering(scene, products, mode);
    const auto context = render::create_headless_context();
    render::Renderer renderer;
    renderer.set_terrain(*products.terrain);
    rendering.apply(renderer);
    // A still picture in one frame: the froxels' lighting takes its jittered samples at once.
    const render::Image image = renderer.render(camera, width, height);
    render::write_png_atomic(a.out, image);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%s\n", a.out.c_str());
    std::fprintf(stderr, "kiri render: %dx%d, mode %s, %.2f s\n", width, height, render::to_string(mode), seconds);
    if (a.timings) {  // the last frame's passes: device time (pass_timer.hpp) and issue time
        const render::FrameStats& stats = renderer.last_stats();
        for (const render::PassTime& t : stats.passes)
            std::fprintf(stderr, "kiri render: pass %-18s gpu %9.2f ms  cpu %9.2f ms\n", t.pass.c_str(), t.gpu_ms,
                         t.cpu_ms);
        std::fprintf(stderr, "kiri render: frame %.2f ms\n", stats.frame_ms);
    }
    if (const geometry::ParticleCloud* particles = rendering.particles()) {
        const render::AttenuationBuffer& b = renderer.attenuation();
        const auto& size = b.grid().size;
        std::fprintf(
            stderr, "kiri render: %zu particles, attenuation buffer %dx%dx%d %s (%.1f MiB), built in %.1f ms\n",
            particles->particles.size(), size[0], size[1], size[2], scene.particles.half_float ? "R16F" : "R32F",
            double(b.texture_bytes()) / 1048576.0, b.last_build_ms());
    }
}

}  // namespace

void add_render_command(CLI::App& app)
{
    auto* sub = app.add_subcommand("render", "Render a scene headless to a PNG and print its path");
    auto a = std::make_shared<RenderArgs>();
    sub->add_option("scene", a->scene, "scene file (JSON)")->required();
    sub->add_option("-o,--out", a->out, "output PNG")->required();
    sub->add_option("--width", a->width, "image width in pixels (default: the scene's)")->check(CLI::Range(1, 16384));
    sub->add_option("--height", a->height, "image height in pixels (default: the scene's)")
        ->check(CLI::Range(1, 16384));
    sub->add_option("--camera", a->camera, "camera name from the scene (default: its first)");
    sub->add_option("--mode", a->mode,
                    "what to draw: terrain, layers (the fog's layer stack), particles (the fog as lit particles), "
                    "froxel (the fog as a volume), combined (each of them drawing its share of the fog: froxels "
                    "near, layers far, particles in the top band), reference (the CPU reference ray marcher of "
                    "that volume: slow), auto (default: combined when the scene has fog, else terrain)")
        ->check(CLI::IsMember({"auto", "terrain", "layers", "particles", "froxel", "combined", "reference"}));
    sub->add_flag("--timings", a->timings, "print the last frame's time per pass");
    sub->callback([a] { run(*a); });
}

}  // namespace kiri::cli
