#include "kiri/geometry/scene/quality.hpp"

#include <nlohmann/json.hpp>

namespace kiri::geometry {

using json = nlohmann::json;

const char* to_string(Quality q)
{
    switch (q) {
    case Quality::low: return "low";
    case Quality::medium: return "medium";
    case Quality::high: return "high";
    default: return "ultra";
    }
}

bool parse_quality(std::string_view name, Quality& out)
{
    for (Quality q : {Quality::low, Quality::medium, Quality::high, Quality::ultra})
        if (name == to_string(q)) {
            out = q;
            return true;
        }
    return false;
}

json quality_preset(Quality q)
{
    // Each step up roughly doubles the cost where it pays most (docs/combined.md's table):
    // froxels near the eye, then layers, then the particles' detail.
    struct Preset {
        int layers;
        double layer_resolution;
        int particles, buffer;
        int froxel_x, froxel_y, slices, pixel_steps;
        double particle_share;
    };
    static constexpr Preset presets[] = {
        {8, 0.25, 4000, 64, 80, 45, 32, 12, 0.0},      // low: no particles
        {12, 0.5, 10000, 96, 120, 68, 48, 16, 0.4},    // medium
        {15, 0.5, 20000, 128, 160, 90, 64, 24, 0.5},   // high: the sections' defaults
        {30, 1.0, 60000, 192, 240, 135, 96, 32, 0.5},  // ultra
    };
    const Preset& p = presets[int(q)];
    return {{"layers", {{"count", p.layers}, {"resolution", p.layer_resolution}}},
            {"particles", {{"count", p.particles}, {"resolution", p.buffer}}},
            {"froxel", {{"size", {p.froxel_x, p.froxel_y, p.slices}}, {"pixel_steps", p.pixel_steps}}},
            {"combined", {{"particle_share", p.particle_share}}}};
}

void apply_quality_preset(json& root, Quality q)
{
    const json preset = quality_preset(q);  // items() refers to it: it must outlive the loop
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
