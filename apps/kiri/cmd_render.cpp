// `kiri render SCENE.json -o OUT.png`: renders a scene headless (EGL) and writes the PNG
// atomically, or the linear radiance before the tone map for OUT.exr. The CPU modes (reference,
// path) need no GL. The output folder is checked before any loading or rendering.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "commands.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/reference/path_tracer.hpp"
#include "kiri/geometry/reference/reference_fog.hpp"
#include "kiri/geometry/scene/dem_scene.hpp"
#include "kiri/geometry/scene/pipeline.hpp"
#include "kiri/render/exr_image.hpp"
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
    bool no_sky = false, black_ground = false;
    int samples = 256, bounces = 128, max_samples = 0;
    double noise = 0.0;
    std::uint64_t seed = 1;
};

// The CPU renderers (reference, path) of the scene's Medium and height fog.
void render_cpu(const RenderArgs& a, const geometry::Scene& scene, const geometry::PipelineProducts& products,
                const render::Camera& camera, int width, int height)
{
    const geometry::Terrain& terrain = *products.terrain;
    const geometry::FroxelOptions options = render::scene_froxel_options(scene, terrain);
    const geometry::Medium* medium = products.medium.get();
    const geometry::ReferenceView view = render::reference_view(camera, width, height, options.far);
    geometry::FogLighting light = render::scene_fog_lighting(scene, &terrain, medium, options, products.light_volume);
    light.sky = !a.no_sky;
    const bool exr = render::is_exr_path(a.out);
    if (a.mode == "reference") {
        geometry::ReferenceOptions ro;
        ro.shade_terrain = !a.black_ground;
        ro.surround = scene.terrain.surround;
        const geometry::ReferenceImage r =
            geometry::render_reference_fog({medium, options.height_fog}, &terrain.heightfield(), view, light, ro);
        if (exr)
            render::write_exr_atomic(a.out, render::linear_radiance(r));
        else
            render::write_png_atomic(a.out, render::tone_mapped(r));
        return;
    }
    geometry::PathTracerOptions po;
    po.samples = a.samples;
    po.max_bounces = a.bounces;
    po.seed = a.seed;
    po.noise_target = a.noise;
    po.max_samples = a.max_samples;
    po.ground = a.black_ground ? geometry::PathGround::black : geometry::PathGround::lambertian;
    po.surround = scene.terrain.surround;
    const geometry::PathTracedImage p =
        geometry::render_path_traced({medium, options.height_fog}, &terrain.heightfield(), view, light, po);
    if (exr)
        render::write_exr_atomic(a.out, render::linear_radiance(p));
    else
        render::write_png_atomic(a.out, render::tone_mapped(p));
    // The noise: mean standard error over mean radiance (luminance).
    double mean = 0.0, error = 0.0, paths = 0.0;
    for (std::size_t k = 0; k < p.radiance.size(); ++k) {
        mean += geometry::luminance(p.radiance[k]);
        error += geometry::luminance(p.std_error[k]);
        paths += p.pixel_samples[k];
    }
    if (a.noise > 0.0)
        std::fprintf(stderr, "kiri render: %d to %d samples per pixel (mean %.0f, %d rounds), ", p.samples,
                     *std::max_element(p.pixel_samples.begin(), p.pixel_samples.end()),
                     paths / std::max<double>(double(p.pixel_samples.size()), 1.0), p.rounds);
    else
        std::fprintf(stderr, "kiri render: %d samples per pixel, ", p.samples);
    std::fprintf(stderr, "at most %d bounces, seed %llu: %.2f %% standard error\n", a.bounces,
                 static_cast<unsigned long long>(a.seed), mean > 0.0 ? 100.0 * error / mean : 0.0);
}

void run(const RenderArgs& a)
{
    const auto start = std::chrono::steady_clock::now();
    check_output_file(a.out);
    // The format is the name's: any other ending would get a PNG's bytes under it.
    if (const std::string ending = std::filesystem::path(a.out).extension().string();
        !render::is_exr_path(a.out) && !render::is_png_path(a.out))
        throw IoError(a.out, "",
                      (ending.empty() ? std::string("has no ending") : "ends in " + ending) +
                          ": kiri render writes a .png (tone-mapped) or an .exr (linear radiance)");
    const geometry::Scene given = geometry::load_scene_or_dem(a.scene);
    const bool cpu = a.mode == "reference" || a.mode == "path";  // the CPU judges: slow, no GL
    if (!(a.noise >= 0.0 && a.noise <= 1.0))                     // NaN passes CLI11's range
        throw InputError(a.scene, "--noise", "must be a fraction between 0 and 1, not " + std::to_string(a.noise));
    if ((a.noise > 0.0 || a.max_samples > 0) && a.mode != "path")
        throw InputError(a.scene, a.noise > 0.0 ? "--noise" : "--max-samples", "only --mode path samples adaptively");
    if (a.max_samples > 0 && a.max_samples < a.samples)
        throw InputError(a.scene, "--max-samples",
                         std::to_string(a.max_samples) + " is under --samples " + std::to_string(a.samples));
    render::FogMode mode = render::default_mode(given);
    if (cpu)
        mode = render::FogMode::froxel;  // the CPU modes draw the Medium and the height fog
    else if (a.mode != "auto")
        render::parse_fog_mode(a.mode, mode);  // CLI11 checked the name
    geometry::Pipeline pipeline;
    const geometry::PipelineProducts products = pipeline.run(given, render::pipeline_target(mode, given));
    const auto authored = std::chrono::steady_clock::now();
    // The scene as the pipeline completed it: the keys the file left out derived from the terrain.
    const geometry::Scene& scene = *products.scene;
    const geometry::Bounds3 bounds = products.terrain->bounds();
    const render::Camera camera = render::to_camera(scene.camera(a.camera, bounds.min, bounds.max));
    const int width = a.width > 0 ? a.width : scene.image.width;
    const int height = a.height > 0 ? a.height : scene.image.height;

    if (cpu) {
        render_cpu(a, scene, products, camera, width, height);
        std::printf("%s\n", a.out.c_str());
        print_derived(*products.derived, products.terrain->heightfield());
        std::fprintf(stderr, "kiri render: %dx%d, mode %s, %.2f s\n", width, height, a.mode.c_str(),
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        return;
    }
    const render::SceneRendering rendering(scene, products, mode);
    const auto context = render::create_headless_context();
    const auto context_made = std::chrono::steady_clock::now();
    render::Renderer renderer;
    renderer.set_terrain(*products.terrain, 1.0, scene.terrain.surround);
    rendering.apply(renderer);
    if (a.no_sky || a.black_ground) {
        render::SunLight sun = rendering.sun();
        sun.sky = !a.no_sky;
        sun.black_ground = a.black_ground;
        renderer.set_sun(sun);
    }
    // A still picture in one frame: the froxels' lighting takes its jittered samples at once.
    const auto drawing = std::chrono::steady_clock::now();
    const render::Image image = renderer.render(camera, width, height);
    const auto drawn = std::chrono::steady_clock::now();
    if (render::is_exr_path(a.out))
        render::write_exr_atomic(a.out, renderer.read_radiance());
    else
        render::write_png_atomic(a.out, image);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%s\n", a.out.c_str());
    // After the picture: a failure stays the one line on stderr.
    print_derived(*products.derived, products.terrain->heightfield());
    std::fprintf(stderr, "kiri render: %dx%d, mode %s, %.2f s\n", width, height, render::to_string(mode), seconds);
    if (a.timings) {  // where a cold start goes: the pipeline's stages, GL, the frame's passes
        auto ms = [](auto from, auto to) { return std::chrono::duration<double, std::milli>(to - from).count(); };
        for (int k = 0; k < geometry::stage_count; ++k)
            if (pipeline.ran(geometry::Stage(k)))
                std::fprintf(stderr, "kiri render: stage %-18s %9.2f ms\n", geometry::to_string(geometry::Stage(k)),
                             1e3 * pipeline.stages()[std::size_t(k)].seconds);
        std::fprintf(stderr, "kiri render: load and author      %9.2f ms\n", ms(start, authored));
        std::fprintf(stderr, "kiri render: GL context           %9.2f ms  %s\n", ms(authored, context_made),
                     context->description().c_str());
        std::fprintf(stderr, "kiri render: uploads and programs %9.2f ms\n", ms(context_made, drawing));
        std::fprintf(stderr, "kiri render: render               %9.2f ms\n", ms(drawing, drawn));
        std::fprintf(stderr, "kiri render: read back and write  %9.2f ms\n",
                     ms(drawn, std::chrono::steady_clock::now()));
        // The last frame's passes: device time (pass_timer.hpp) and issue time.
        const render::FrameStats& stats = renderer.last_stats();
        for (const render::PassTime& t : stats.passes)
            std::fprintf(stderr, "kiri render: pass %-18s gpu %9.2f ms  cpu %9.2f ms\n", t.pass.c_str(), t.gpu_ms,
                         t.cpu_ms);
        std::fprintf(stderr, "kiri render: frame %.2f ms\n", stats.frame_ms);
        if (stats.layers > 0)
            std::fprintf(stderr, "kiri render: %d layers above the base, %d triangles each (level of detail)\n",
                         stats.layers, stats.layer_triangles);
        if (stats.refined_shade_vertices > 0)
            std::fprintf(stderr,
                         "kiri render: the fog's shade on the ground read from a finer map around %d of %d vertices "
                         "(%.1f %%), interpolated elsewhere\n",
                         stats.refined_shade_vertices, stats.terrain_vertices,
                         100.0 * stats.refined_shade_vertices / stats.terrain_vertices);
        if (stats.froxel.applied_pixels > 0)
            std::fprintf(
                stderr,
                "kiri render: froxel apply marched %d of %d pixels (%.1f %%), took the mean of the marched "
                "samples around them at %d (%.1f %%), read the volume elsewhere; %d pixels (%.1f %%) saw "
                "different fog among their samples and marched each sample's ray (%d of them one surface fogged "
                "unevenly, the others two surfaces)\n",
                stats.froxel.marched_pixels, stats.froxel.applied_pixels,
                100.0 * stats.froxel.marched_pixels / stats.froxel.applied_pixels, stats.froxel.upsampled_pixels,
                100.0 * stats.froxel.upsampled_pixels / stats.froxel.applied_pixels, stats.froxel.edge_pixels,
                100.0 * stats.froxel.edge_pixels / stats.froxel.applied_pixels, stats.froxel.fog_split_pixels);
    }
    if (const geometry::ParticleCloud* particles = rendering.particles()) {
        const render::AttenuationBuffer& b = renderer.attenuation();
        const auto& size = b.grid().size;
        std::fprintf(stderr,
                     "kiri render: %zu particles of %zu candidates (%zu trials), attenuation buffer %dx%dx%d %s "
                     "(%.1f MiB), built in %.1f ms\n",
                     particles->particles.size(), particles->candidate_count, particles->trial_count, size[0], size[1],
                     size[2], scene.particles.half_float ? "R16F" : "R32F", double(b.texture_bytes()) / 1048576.0,
                     b.last_build_ms());
        if (a.timings && renderer.last_stats().particles > 0)
            std::fprintf(stderr,
                         "kiri render: particles: %d billboards in view of %d, %d of them near (coarser), blended "
                         "%llu fragments, per-particle light %.2f MiB\n",
                         renderer.last_stats().particles_drawn, renderer.last_stats().particles,
                         renderer.last_stats().near_particles,
                         (unsigned long long)renderer.last_stats().particle_fragments,
                         double(renderer.last_stats().particle_light_bytes) / 1048576.0);
    }
}

}  // namespace

void add_render_command(CLI::App& app)
{
    auto* sub = app.add_subcommand(
        "render", "Render a scene headless to a PNG (or its linear radiance to an OpenEXR file) and print its path");
    auto a = std::make_shared<RenderArgs>();
    sub->add_option("scene", a->scene,
                    "scene file (JSON), or a DEM: its terrain with a valley fog, every other key derived")
        ->required();
    sub->add_option("-o,--out", a->out,
                    "output file: a PNG (tone-mapped), or the linear radiance before the tone map when it ends in "
                    ".exr (OpenEXR, 32-bit float RGBA)")
        ->required();
    sub->add_option("--width", a->width, "image width in pixels (default: the scene's)")->check(CLI::Range(1, 16384));
    sub->add_option("--height", a->height, "image height in pixels (default: the scene's)")
        ->check(CLI::Range(1, 16384));
    sub->add_option("--camera", a->camera, "camera name from the scene (default: its first)");
    sub->add_option("--mode", a->mode,
                    "what to draw: terrain, layers (the fog's layer stack), particles (the fog as lit particles), "
                    "froxel (the fog as a volume), combined (each of them drawing its share of the fog: froxels "
                    "at every distance, or near and the layers far when the scene's combined section sets "
                    "near_end, particles in the top band), reference (the CPU reference ray marcher of "
                    "that volume: slow), path (the CPU path tracer of that volume, every order of scattering: "
                    "slower, noisy), auto (default: combined when the scene has fog, else terrain)")
        ->check(CLI::IsMember({"auto", "terrain", "layers", "particles", "froxel", "combined", "reference", "path"}));
    sub->add_option(
           "--samples", a->samples,
           "--mode path: paths per pixel (default 256: the default scene at 160x90 in about a minute on 2 cores)")
        ->check(CLI::Range(1, 1 << 20));
    sub->add_option("--noise", a->noise,
                    "--mode path: adaptive sampling; each block of 4x4 pixels whose mean has a relative standard "
                    "error above this (0.03: 3 %) takes more paths, fourfold a round, up to --max-samples (default "
                    "0: off)")
        ->check(CLI::Range(0.0, 1.0));
    sub->add_option("--max-samples", a->max_samples,
                    "--mode path with --noise: the most paths a pixel takes (default 64 x --samples)")
        ->check(CLI::Range(1, 1 << 26));
    sub->add_option("--bounces", a->bounces, "--mode path: most scattering events per path (default 128)")
        ->check(CLI::Range(0, 1 << 20));
    sub->add_option("--seed", a->seed, "--mode path: random seed (default 1; the same seed gives the same image)");
    sub->add_flag("--no-sky", a->no_sky,
                  "no sky light: no ambient, a black sky without the sun's glow (to compare with renderers set up "
                  "in a black world)");
    sub->add_flag("--black-ground", a->black_ground,
                  "a black terrain and ground beyond it (they still hide and shadow), so the picture is the fog's "
                  "light alone (with --no-sky: to composite, or to compare with --mode path)");
    sub->add_flag("--timings", a->timings, "print the last frame's time per pass");
    sub->callback([a] { run(*a); });
}

}  // namespace kiri::cli
