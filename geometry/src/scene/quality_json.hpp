#pragma once
// Internal: a quality preset (quality.hpp) applied to a scene's JSON.
#include <nlohmann/json.hpp>

#include "kiri/geometry/scene/quality.hpp"

namespace kiri::geometry {

//! Adds the preset's keys to the scene JSON `root` where the scene does not set them, each
//! under its section's own key (the sections' field lists name them).
void apply_quality_preset(nlohmann::json& root, Quality q);

}  // namespace kiri::geometry
