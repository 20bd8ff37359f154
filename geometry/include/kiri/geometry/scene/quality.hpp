#pragma once
//! \file quality.hpp
//! Quality presets (docs/combined.md): one word that sets how much each fog renderer spends,
//! layer count and resolution, particles and their attenuation buffer, the froxel volume and
//! the particles' share of the fog. A scene's "quality" key applies a preset under its own
//! keys: whatever the scene writes itself wins. The measured cost and error of each preset are
//! in docs/combined.md (`kiri bench --stage presets`).
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

namespace kiri::geometry {

enum class Quality { low, medium, high, ultra };

const char* to_string(Quality q);
//! False for any other name.
bool parse_quality(std::string_view name, Quality& out);

//! The preset as scene sections, e.g. {"layers": {"count": 15, ...}, "froxel": {...}, ...}.
nlohmann::json quality_preset(Quality q);

//! Adds the preset's keys to the scene JSON `root` where the scene does not set them.
void apply_quality_preset(nlohmann::json& root, Quality q);

}  // namespace kiri::geometry
