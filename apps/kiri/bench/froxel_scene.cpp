#include "bench/froxel_scene.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "kiri/render/scene_rendering.hpp"

namespace kiri::bench {

FroxelBenchScene::FroxelBenchScene(const std::filesystem::path& scene_file)
    : scene(geometry::load_scene(scene_file)), terrain(geometry::load_scene_terrain(scene)),
      fog(geometry::author_scene_fog(scene, terrain))
{
    context = render::create_headless_context();
    renderer = std::make_unique<render::Renderer>();
    renderer->set_terrain(terrain);
    const auto& s = scene.sun;
    renderer->set_sun({s.direction, s.color, s.intensity, s.ambient});
    const geometry::Bounds3 b = terrain.bounds();
    const geometry::CameraSpec c = scene.camera("", b.min, b.max);
    camera.position = c.position;
    camera.target = c.target;
    camera.fov_y_deg = c.fov_y_deg;
}

geometry::FroxelOptions FroxelBenchScene::options() const
{
    geometry::FroxelOptions o = geometry::world_froxel_options(scene);
    const geometry::Bounds3 b = terrain.bounds();
    o.height_fog.min = {b.min.x, b.min.y};
    o.height_fog.max = {b.max.x, b.max.y};
    o.temporal = false;
    o.far = 60000.0;
    return o;
}

geometry::FogLighting FroxelBenchScene::lighting(const geometry::FroxelOptions& o) const
{
    geometry::FogLighting l;
    l.sun_direction = scene.sun.direction;
    l.sun_radiance = scene.sun.color * scene.sun.intensity;
    l.ambient = scene.sun.ambient;
    l.terrain_shadows = o.terrain_shadows;
    l.fog_shadows = o.fog_shadows;
    l.scattering_octaves = geometry::scattering_octaves_of(&fog.medium);
    return l;
}

geometry::ReferenceView FroxelBenchScene::view(int width, int height, const geometry::FroxelOptions& o) const
{
    return render::reference_view(camera, width, height, o.far);
}

double FroxelBenchScene::frame_seconds(const geometry::FroxelOptions& o, const render::Camera& c, int width, int height,
                                       int frames)
{
    renderer->set_froxel_fog(&fog.medium, o);
    const double t0 = fog.medium.detail().time;
    std::vector<double> t;
    for (int k = -1; k < frames; ++k) {
        // A new time each frame: the volume's passes all rerun (the drift of a windless fog
        // changes nothing else).
        fog.medium.set_time(t0 + 1e-3 * (k + 2));
        const auto start = std::chrono::steady_clock::now();
        renderer->draw(c, width, height);
        if (k >= 0)  // the first frame builds the shadow map and compiles the shaders
            t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    fog.medium.set_time(t0);
    std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
    return t[t.size() / 2];
}

render::FogError FroxelBenchScene::error(const geometry::FroxelOptions& o, const geometry::ReferenceImage& reference)
{
    renderer->set_froxel_fog(&fog.medium, o);
    renderer->render(camera, reference.width, reference.height);
    return render::compare_fog(renderer->read_froxel_fog(), reference);
}

render::Image tone_mapped(const geometry::ReferenceImage& r)
{
    render::Image image{r.width, r.height, std::vector<std::uint8_t>(std::size_t(r.width) * r.height * 4, 255)};
    for (std::size_t k = 0; k < r.inscatter.size(); ++k) {
        const glm::dvec3 c = r.composed(k);
        for (int ch = 0; ch < 3; ++ch)
            image.rgba[4 * k + std::size_t(ch)] =
                std::uint8_t(std::lround(255.0 * std::pow(1.0 - std::exp(-c[ch] * 0.7), 1.0 / 2.2)));
    }
    return image;
}

}  // namespace kiri::bench
