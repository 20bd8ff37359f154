#include "bench/froxel_scene.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "kiri/render/scene_rendering.hpp"

namespace kiri::bench {

FroxelBenchScene::FroxelBenchScene(const std::filesystem::path& scene_file)
    : scene(geometry::load_scene(scene_file)), products(geometry::author_scene(scene, {geometry::Stage::medium})),
      terrain(*products.terrain), medium(*products.medium)
{
    context = render::create_headless_context();
    renderer = std::make_unique<render::Renderer>();
    renderer->set_terrain(terrain);
    renderer->set_sun(render::to_sun(scene.sun));
    const geometry::Bounds3 b = terrain.bounds();
    camera = render::to_camera(scene.camera("", b.min, b.max));
}

geometry::FroxelOptions FroxelBenchScene::options() const
{
    geometry::FroxelOptions o = render::scene_froxel_options(scene, terrain);
    o.temporal = false;
    o.far = 60000.0;
    return o;
}

geometry::FogLighting FroxelBenchScene::lighting(const geometry::FroxelOptions& o) const
{
    return render::scene_fog_lighting(scene, &terrain, &medium, o);
}

geometry::ReferenceView FroxelBenchScene::view(int width, int height, const geometry::FroxelOptions& o) const
{
    return render::reference_view(camera, width, height, o.far);
}

double FroxelBenchScene::frame_seconds(const geometry::FroxelOptions& o, const render::Camera& c, int width, int height,
                                       int frames)
{
    renderer->set_froxel_fog(&medium, o);
    const double t0 = medium.detail().time;
    std::vector<double> t;
    for (int k = -1; k < frames; ++k) {
        // A new time each frame: the volume's passes all rerun (the drift of a windless fog
        // changes nothing else).
        medium.set_time(t0 + 1e-3 * (k + 2));
        const auto start = std::chrono::steady_clock::now();
        renderer->draw(c, width, height);
        if (k >= 0)  // the first frame builds the shadow map and compiles the shaders
            t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    medium.set_time(t0);
    std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
    return t[t.size() / 2];
}

render::FogError FroxelBenchScene::error(const geometry::FroxelOptions& o, const geometry::ReferenceImage& reference)
{
    renderer->set_froxel_fog(&medium, o);
    renderer->render(camera, reference.width, reference.height);
    return render::compare_fog(renderer->read_froxel_fog(), reference);
}

}  // namespace kiri::bench
