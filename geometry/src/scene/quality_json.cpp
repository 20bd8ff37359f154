#include "scene/quality_json.hpp"

#include <set>
#include <string>

#include "kiri/geometry/layers/layer_stack.hpp"
#include "kiri/geometry/medium/fog_partition.hpp"
#include "kiri/geometry/particles/particles.hpp"
#include "kiri/geometry/volume/froxel_options.hpp"
#include "scene/field_json.hpp"

namespace kiri::geometry {
namespace {

using json = nlohmann::json;

// The keys of the given members of o, written as o's section writes them.
template <class O, class... Members>
json section_keys(const O& o, const Members&... members)
{
    const std::set<std::string> keys = {std::string(field_of(o, members).key)...};
    const json all = write_fields(o);  // items() refers to it: it must outlive the loop
    json out = json::object();
    for (const auto& [key, value] : all.items())
        if (keys.count(key))
            out[key] = value;
    return out;
}

json preset_sections(const QualityPreset& p)
{
    LayerOptions layers;
    layers.count = p.layers;
    layers.resolution = p.layer_resolution;
    ParticleOptions particles;
    particles.count = p.particles;
    particles.resolution = p.attenuation_resolution;
    FroxelOptions froxel;
    froxel.width = p.froxel_width;
    froxel.height = p.froxel_height;
    froxel.slices = p.froxel_slices;
    froxel.pixel_steps = p.froxel_pixel_steps;
    FogPartition combined;
    combined.particle_share = p.particle_share;
    return {{"layers", section_keys(layers, layers.count, layers.resolution)},
            {"particles", section_keys(particles, particles.count, particles.resolution)},
            {"froxel", section_keys(froxel, froxel.width, froxel.pixel_steps)},
            {"combined", section_keys(combined, combined.particle_share)}};
}

}  // namespace

void apply_quality_preset(json& root, Quality q)
{
    const json preset = preset_sections(quality_preset(q));  // items() refers to it: it must outlive the loop
    for (const auto& [section, keys] : preset.items()) {
        if (!root.contains(section))
            root[section] = json::object();
        json& target = root[section];
        if (!target.is_object())  // a wrong type is left for the section's reader to report
            continue;
        for (const auto& [key, value] : keys.items())
            if (!target.contains(key))
                target[key] = value;
    }
}

}  // namespace kiri::geometry
