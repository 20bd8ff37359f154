#pragma once
// Internal: the scene's "medium" section <-> JSON.
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "kiri/geometry/medium/medium.hpp"

namespace kiri::geometry {

//! At most one of extinction (1/m), visibility (m, Koschmieder) or liquid_water_content (g/m^3,
//! with droplet_radius in micrometres, default 7) sets the extinction.
//! \throw InputError(file, "/medium/...", reason); unknown keys are errors.
MediumOptions parse_medium_options(const nlohmann::json& j, const std::string& file);
nlohmann::json medium_options_to_json(const MediumOptions& options);

//! The medium's motion keys (detail, detail_scale, wind, time, dissipation_half_life): the
//! "layers" section gave them before the medium owned them, and still may.
std::set<std::string> medium_keys_in_layers();
//! Those keys given in the "layers" section `layers`, written into `o` (the medium's options).
//! \throw InputError when the "medium" section `medium` (null if none) gives one of them too.
void read_layer_aliases(const nlohmann::json& layers, const nlohmann::json* medium, const std::string& file,
                        MediumOptions& o);

}  // namespace kiri::geometry
