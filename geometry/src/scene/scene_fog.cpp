#include "kiri/geometry/scene_fog.hpp"

#include <chrono>

#include "kiri/geometry/author_estimate.hpp"
#include "kiri/geometry/error.hpp"

namespace kiri::geometry {

SceneFog author_scene_fog(const Scene& scene, const Terrain& terrain)
{
    const std::string label = scene.file.string();
    if (!scene.fog)
        throw InputError(label, "/fog", "the scene has no fog section");
    LayerOptions layers = world_layer_options(scene);
    const FogSpec spec = world_fog_spec(scene);
    if (spec.fit.mode == FitMode::lake)
        layers.base_offset = -layers.thickness;
    check_author_estimate(estimate_author(spec, terrain.heightfield(), layers.count), label);
    SceneFog fog{author_base_surface(terrain, spec, label), layers, {}, {}, 0.0, 0.0};
    const auto start = std::chrono::steady_clock::now();
    fog.base = make_layer_base(fog.authored.surface, fog.authored.tessellation, fog.layers, label);
    const auto made_base = std::chrono::steady_clock::now();
    fog.seconds_layer_base = std::chrono::duration<double>(made_base - start).count();
    fog.medium = make_medium(fog.base, fog.layers, terrain, scene.medium, label);
    fog.seconds_medium = std::chrono::duration<double>(std::chrono::steady_clock::now() - made_base).count();
    return fog;
}

}  // namespace kiri::geometry
