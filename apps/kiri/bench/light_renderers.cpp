#include "bench/light_renderers.hpp"

#include "bench/fog_judge.hpp"
#include "kiri/geometry/reference/reference_fog.hpp"
#include "kiri/geometry/scene/pipeline.hpp"
#include "kiri/render/scene_rendering.hpp"

namespace kiri::bench {

LightFrames::LightFrames() : context_(render::create_headless_context()) {}

std::vector<double> LightFrames::luminance(const std::filesystem::path& scene_file, const std::string& camera,
                                           render::FogMode mode, int width, int height, int scale)
{
    const SceneJson source(scene_file);
    nlohmann::json root = source.root;
    root["medium"]["multiple_scattering"] = "baked";
    const geometry::Scene given = source.parse(root);
    const geometry::PipelineProducts products = geometry::author_scene(given, render::pipeline_target(mode, given));
    const geometry::Scene& scene = *products.scene;
    if ((mode == render::FogMode::layers || mode == render::FogMode::particles) &&
        render::scene_froxel_options(scene, *products.terrain).height_fog.enabled())
        return {};
    const geometry::Bounds3 bounds = products.terrain->bounds();
    const render::Camera view = render::to_camera(scene.camera(camera, bounds.min, bounds.max));
    const render::SceneRendering rendering(scene, products, mode);
    render::Renderer renderer;
    renderer.set_terrain(*products.terrain, 1.0, scene.terrain.surround);
    rendering.apply(renderer);
    render::SunLight sun = rendering.sun();
    sun.sky = false;
    sun.black_ground = true;
    renderer.set_sun(sun);
    renderer.render(view, width * scale, height * scale);
    const render::RadianceImage frame = renderer.read_radiance();
    // Each judge pixel: the frame's pixels around its centre (the 2x2 about it for an even
    // scale), where the path tracer's one ray runs.
    const int lo = (scale - 1) / 2, hi = scale / 2;
    std::vector<double> out(std::size_t(width) * height, 0.0);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int dy = lo; dy <= hi; ++dy)
                for (int dx = lo; dx <= hi; ++dx) {
                    const float* p = &frame.rgba[(std::size_t(y * scale + dy) * frame.width + x * scale + dx) * 4];
                    out[std::size_t(y) * width + x] +=
                        geometry::luminance({p[0], p[1], p[2]}) / double((hi - lo + 1) * (hi - lo + 1));
                }
    return out;
}

}  // namespace kiri::bench
