#pragma once
// Internal: the fog section's placement keys ("fill", "outline", "flow", "burn_off") <-> JSON.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "kiri/geometry/placement/fog_placement.hpp"
#include "core/json_reader.hpp"

namespace kiri::geometry {

//! The placement of the fog object `fog` at pointer p ("/fog"), or nothing when it has no
//! "fill". Relative mask paths are resolved against base_dir. \throw InputError.
std::optional<PlacementSpec> parse_placement(const nlohmann::json& fog, const JsonReader& r, const std::string& p,
                                             const std::filesystem::path& base_dir);
//! The fog section's keys that a fill sets itself (refused beside it, left out when writing it).
std::vector<std::string> keys_set_by_fill();
//! Adds the placement's keys to a fog object.
void placement_to_json(const PlacementSpec& spec, nlohmann::json& fog);

}  // namespace kiri::geometry
