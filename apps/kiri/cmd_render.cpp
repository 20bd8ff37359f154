// `kiri render SCENE.json -o OUT.png`: renders a scene headless (EGL) and writes the PNG
// atomically. The output folder is checked before any loading or rendering.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "commands.hpp"
#include "kiri/geometry/particles.hpp"
#include "kiri/geometry/error.hpp"
#include "kiri/geometry/reference_fog.hpp"
#include "kiri/geometry/scene.hpp"
#include "kiri/geometry/scene_fog.hpp"
#include "kiri/geometry/terrain.hpp"
#include "kiri/render/gl_context.hpp"
#include "kiri/render/renderer.hpp"

namespace kiri::cli {
namespace {

struct RenderArgs {
    std::string scene, out, camera, mode = "auto";
    int width = 0, height = 0;
};

render::Camera to_camera(const geometry::CameraSpec& c)
{
    render::Camera out;
    out.position = c.position;
    out.target = c.target;
    out.fov_y_deg = c.fov_y_deg;
    return out;
}

render::SunLight to_sun(const geometry::SunSpec& s) { return {s.direction, s.color, s.intensity, s.ambient}; }

render::ParticleStyle to_style(const geometry::ParticleOptions& o)
{
    render::ParticleStyle s;
    s.buffer.resolution = o.resolution;
    s.buffer.half_float = o.half_float;
    s.buffer.frame = o.frame;
    s.soft_edge = o.soft_edge;
    return s;
}

// The scene's fog (Medium and height fog) by the CPU reference ray marcher, tone mapped like the
// shaders (exposure 0.7, gamma 2.2) over the reference's own terrain and sky.
// The scene's froxel options in world units, its height fog over the terrain's extent only.
geometry::FroxelOptions froxel_options(const geometry::Scene& scene, const geometry::Terrain& terrain)
{
    geometry::FroxelOptions options = geometry::world_froxel_options(scene);
    const geometry::Bounds3 b = terrain.bounds();
    options.height_fog.min = {b.min.x, b.min.y};
    options.height_fog.max = {b.max.x, b.max.y};
    return options;
}

void render_reference(const geometry::Scene& scene, const geometry::Terrain& terrain, const render::Camera& camera,
                      int width, int height, const std::string& out)
{
    const geometry::FroxelOptions options = froxel_options(scene, terrain);
    std::optional<geometry::SceneFog> fog;
    if (scene.fog)
        fog = geometry::author_scene_fog(scene, terrain);
    geometry::ReferenceView view;
    view.eye = camera.position;
    view.target = camera.target;
    view.fov_y_deg = camera.fov_y_deg;
    view.width = width;
    view.height = height;
    view.max_depth = options.far;
    geometry::FogLighting light;
    light.sun_direction = scene.sun.direction;
    light.sun_radiance = scene.sun.color * scene.sun.intensity;
    light.ambient = scene.sun.ambient;
    light.terrain_shadows = options.terrain_shadows;
    light.fog_shadows = options.fog_shadows;
    light.scattering_octaves = geometry::scattering_octaves_of(fog ? &fog->medium : nullptr);
    const geometry::ReferenceImage r = geometry::render_reference_fog({fog ? &fog->medium : nullptr, options.height_fog},
                                                                      &terrain.heightfield(), view, light);
    render::Image image{width, height, std::vector<std::uint8_t>(std::size_t(width) * height * 4, 255)};
    for (std::size_t k = 0; k < r.inscatter.size(); ++k) {
        const glm::dvec3 c = r.composed(k);
        for (int ch = 0; ch < 3; ++ch)
            image.rgba[4 * k + std::size_t(ch)] =
                std::uint8_t(std::lround(255.0 * std::pow(1.0 - std::exp(-c[ch] * 0.7), 1.0 / 2.2)));
    }
    render::write_png_atomic(out, image);
}

void run(const RenderArgs& a)
{
    const auto start = std::chrono::steady_clock::now();
    check_output_file(a.out);
    const geometry::Scene scene = geometry::load_scene(a.scene);
    const geometry::Terrain terrain = geometry::load_scene_terrain(scene);
    const geometry::Bounds3 bounds = terrain.bounds();
    const render::Camera camera = to_camera(scene.camera(a.camera, bounds.min, bounds.max));
    const int width = a.width > 0 ? a.width : scene.image.width;
    const int height = a.height > 0 ? a.height : scene.image.height;

    if (a.mode == "reference") {  // the CPU judge: slow, no GL
        render_reference(scene, terrain, camera, width, height, a.out);
        std::printf("%s\n", a.out.c_str());
        std::fprintf(stderr, "kiri render: %dx%d, mode reference, %.2f s\n", width, height,
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        return;
    }
    const auto context = render::create_headless_context();
    render::Renderer renderer;
    renderer.set_terrain(terrain);
    renderer.set_sun(to_sun(scene.sun));
    // "auto" draws what the scene has: its fog as layers when it has a fog section.
    const std::string mode = a.mode != "auto" ? a.mode : scene.fog ? "layers" : "terrain";
    std::optional<geometry::SceneFog> fog;
    std::optional<geometry::ParticleCloud> particles;
    if (mode == "layers") {
        fog = geometry::author_scene_fog(scene, terrain);
        renderer.set_layers(fog->base, fog->layers);
    }
    if (mode == "particles") {  // the fog's medium sampled into particles (docs/particles.md)
        fog = geometry::author_scene_fog(scene, terrain);
        particles = geometry::sample_particles(fog->medium, scene.particles, scene.file.string());
        renderer.set_particles(*particles, to_style(scene.particles));
    }
    if (mode == "froxel") {  // the fog as a volume (docs/froxel.md): the Medium and the height fog
        const geometry::FroxelOptions options = froxel_options(scene, terrain);
        if (!scene.fog && !options.height_fog.enabled())
            throw InputError(a.scene, "/fog", "--mode froxel needs a fog section or a froxel height fog");
        if (scene.fog)
            fog = geometry::author_scene_fog(scene, terrain);
        renderer.set_froxel_fog(fog ? &fog->medium : nullptr, options);
        // A still picture: the temporal filter's jittered frames first (its 16-frame Halton
        // cycle), so the lighting's shadow edges are averaged over each froxel, not aliased.
        if (options.temporal)
            for (int frame = 0; frame < 15; ++frame)
                renderer.draw(camera, width, height);
    }
    const render::Image image = renderer.render(camera, width, height);
    render::write_png_atomic(a.out, image);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%s\n", a.out.c_str());
    std::fprintf(stderr, "kiri render: %dx%d, mode %s, %.2f s\n", width, height, mode.c_str(), seconds);
    if (particles) {
        const render::AttenuationBuffer& b = renderer.attenuation();
        const auto& size = b.grid().size;
        std::fprintf(stderr, "kiri render: %zu particles, attenuation buffer %dx%dx%d %s (%.1f MiB), built in %.1f ms\n",
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
    sub->add_option("--height", a->height, "image height in pixels (default: the scene's)")->check(CLI::Range(1, 16384));
    sub->add_option("--camera", a->camera, "camera name from the scene (default: its first)");
    sub->add_option("--mode", a->mode,
                    "what to draw: terrain, layers (the fog's layer stack), particles (the fog as lit particles), "
                    "froxel (the fog as a volume), reference (the CPU reference ray marcher of that volume: slow), "
                    "auto (layers when the scene has fog)")
        ->check(CLI::IsMember({"auto", "terrain", "layers", "particles", "froxel", "reference"}));
    sub->callback([a] { run(*a); });
}

}  // namespace kiri::cli
