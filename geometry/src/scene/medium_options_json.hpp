#pragma once
// Internal: the scene's "medium" section <-> JSON.
#include <string>

#include <nlohmann/json.hpp>

#include "kiri/geometry/medium/medium.hpp"

namespace kiri::geometry {

//! At most one of extinction (1/m), visibility (m, Koschmieder) or liquid_water_content (g/m^3,
//! with droplet_radius in micrometres, default 7) sets the extinction.
//! \throw InputError(file, "/medium/...", reason); unknown keys are errors.
MediumOptions parse_medium_options(const nlohmann::json& j, const std::string& file);
nlohmann::json medium_options_to_json(const MediumOptions& options);

}  // namespace kiri::geometry
