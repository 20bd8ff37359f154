#include "bench/layers_scene.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "kiri/render/scene_rendering.hpp"

namespace kiri::bench {

namespace {
constexpr double half_size = 1500.0;  // metres: the fog covers [-1500, 1500]^2
}

namespace {
geometry::Scene bench_scene(const std::filesystem::path& data_dir)
{
    geometry::Scene scene = geometry::load_scene(data_dir / "scenes/jacksboro.json");
    scene.fog->footprint = geometry::rectangle_footprint({-half_size, -half_size}, {half_size, half_size});
    scene.fog->patch_size = 1000.0;
    return scene;
}
}  // namespace

LayerBenchScene::LayerBenchScene(const std::filesystem::path& data_dir)
    : scene(bench_scene(data_dir)), terrain(*pipeline.run(scene, {geometry::Stage::terrain}).terrain)
{
    context = render::create_headless_context();
    renderer = std::make_unique<render::Renderer>();
    renderer->set_terrain(terrain);
    renderer->set_sun(render::to_sun(scene.sun));
}

LayerFog LayerBenchScene::fog(int level, int count, double fade_width)
{
    geometry::Scene copy = scene;
    copy.layers.texture.fade_width = fade_width;
    copy.fog->tessellation.level = level;
    copy.layers.count = count;
    copy.layers.max_count = std::max(copy.layers.max_count, count);
    const geometry::PipelineProducts& fog = pipeline.run(copy, {geometry::Stage::layer_base});
    return {fog.layer_base, fog.layers};
}

namespace {
double ground_at_centre(const geometry::Terrain& t) { return t.height(0.0, 0.0); }
}  // namespace

render::Camera LayerBenchScene::oblique() const
{
    render::Camera c;
    const double z = ground_at_centre(terrain) + 150.0;
    c.target = {0.0, 0.0, z};
    const double d = 2300.0, down = 28.0 * M_PI / 180.0;
    c.position = c.target + d * glm::dvec3(-std::cos(down) * 0.5, -std::cos(down) * std::sqrt(0.75), std::sin(down));
    c.fov_y_deg = 45.0;
    return c;
}

render::Camera LayerBenchScene::side_near() const
{
    // Just outside the fog's west edge, a little above the stack, looking across it.
    render::Camera c;
    const double x = -half_size + 150.0, y = -200.0;
    const double ground = terrain.height(x, y);
    c.position = {x, y, ground + 230.0};
    c.target = {half_size, 200.0, ground + 120.0};
    c.fov_y_deg = 55.0;
    return c;
}

render::Camera LayerBenchScene::top() const
{
    render::Camera c;
    const double z = ground_at_centre(terrain);
    // Straight down over the fog's south-west corner, close enough to see its outline.
    c.position = {-half_size + 300.0, -half_size + 299.0, z + 2600.0};
    c.target = {-half_size + 300.0, -half_size + 300.0, z};
    c.fov_y_deg = 40.0;
    return c;
}

render::Camera LayerBenchScene::away() const
{
    render::Camera c;
    const double z = ground_at_centre(terrain);
    c.position = {0.0, -4000.0, z + 1200.0};
    c.target = {0.0, -14000.0, z};
    return c;
}

double LayerBenchScene::frame_seconds(const render::Camera& camera, int width, int height, int frames)
{
    renderer->draw(camera, width, height);
    renderer->draw(camera, width, height);
    std::vector<double> t;
    for (int k = 0; k < frames; ++k) {
        const auto start = std::chrono::steady_clock::now();
        renderer->draw(camera, width, height);
        t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
    return t[t.size() / 2];
}

double mean_abs_difference(const render::Image& a, const render::Image& b)
{
    double sum = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.rgba.size() && i < b.rgba.size(); ++i) {
        if (i % 4 == 3)
            continue;
        sum += std::abs(int(a.rgba[i]) - int(b.rgba[i]));
        ++n;
    }
    return n ? sum / double(n) : 0.0;
}

double changed_fraction(const render::Image& a, const render::Image& b)
{
    std::size_t changed = 0;
    const std::size_t pixels = std::min(a.rgba.size(), b.rgba.size()) / 4;
    for (std::size_t p = 0; p < pixels; ++p)
        for (int k = 0; k < 3; ++k)
            if (std::abs(int(a.rgba[p * 4 + k]) - int(b.rgba[p * 4 + k])) > 2) {
                ++changed;
                break;
            }
    return pixels ? double(changed) / double(pixels) : 0.0;
}

}  // namespace kiri::bench
