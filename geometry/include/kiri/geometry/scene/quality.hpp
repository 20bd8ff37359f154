#pragma once
//! \file quality.hpp
//! Quality presets (docs/combined.md): one word that sets how much each fog renderer spends,
//! layer count and resolution, particles and their attenuation buffer, the froxel volume and
//! the particles' share of the fog. A scene's "quality" key applies a preset under its own
//! keys: whatever the scene writes itself wins. The measured cost and error of each preset are
//! in docs/combined.md (`kiri bench --stage presets`).
#include <string_view>

namespace kiri::geometry {

enum class Quality { low, medium, high, ultra };

const char* to_string(Quality q);
//! False for any other name.
bool parse_quality(std::string_view name, Quality& out);

//! What a preset sets: layers.count and .resolution, particles.count and .resolution (the
//! attenuation buffer's), froxel.size and .pixel_steps, combined.particle_share.
struct QualityPreset {
    int layers = 15;
    double layer_resolution = 0.5;
    int particles = 20000, attenuation_resolution = 128;
    int froxel_width = 160, froxel_height = 90, froxel_slices = 64, froxel_pixel_steps = 24;
    double particle_share = 0.5;
    bool operator==(const QualityPreset&) const = default;
};
QualityPreset quality_preset(Quality q);

}  // namespace kiri::geometry
