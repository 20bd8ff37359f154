#include "kiri/geometry/scene/scene_fog.hpp"

#include <chrono>

#include "kiri/geometry/scene/author_estimate.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/layers/layer_medium.hpp"
#include "kiri/geometry/placement/fill_medium.hpp"

namespace kiri::geometry {

SceneFog author_scene_fog(const Scene& scene, const Terrain& terrain)
{
    const std::string label = scene.file.string();
    if (!scene.fog)
        throw InputError(label, "/fog", "the scene has no fog section");
    LayerOptions layers = world_layer_options(scene);
    FogSpec spec = world_fog_spec(scene);
    std::optional<PlacedFog> placed;
    if (spec.placement) {
        // Fog placed by the terrain: its footprint and lake target, and a stack as deep as the
        // deepest fog, hanging from the top like a lake's.
        check_author_estimate(estimate_author(spec, terrain.heightfield(), layers.count), label);
        placed = place_fog(terrain, *spec.placement, spec.patch_size, label);
        spec = placed_fog_spec(spec, *placed);
        layers.thickness = spec.fit.thickness;
        validate_layer_options(layers, label);
    }
    if (spec.fit.mode == FitMode::lake)
        layers.base_offset = -layers.thickness;
    check_author_estimate(estimate_author(spec, terrain.heightfield(), layers.count), label);
    SceneFog fog{author_base_surface(terrain, spec, label), layers, {}, {}, 0.0, 0.0};
    const auto start = std::chrono::steady_clock::now();
    fog.base = make_layer_base(fog.authored.surface, fog.authored.tessellation, fog.layers, label);
    const auto made_base = std::chrono::steady_clock::now();
    fog.seconds_layer_base = std::chrono::duration<double>(made_base - start).count();
    fog.medium = placed
        ? fill_medium(terrain, *placed, scene.medium, medium_detail(scene.medium, fog.layers.count), label)
        : make_medium(fog.base, fog.layers, terrain, scene.medium, label);
    fog.placed = std::move(placed);
    fog.seconds_medium = std::chrono::duration<double>(std::chrono::steady_clock::now() - made_base).count();
    return fog;
}

}  // namespace kiri::geometry
