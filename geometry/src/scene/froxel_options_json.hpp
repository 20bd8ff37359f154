#pragma once
// Internal: the scene's "froxel" section <-> JSON.
#include <string>

#include <nlohmann/json.hpp>

#include "kiri/geometry/volume/froxel_options.hpp"

namespace kiri::geometry {

//! \throw InputError(file, "/froxel/...", reason); unknown keys are errors.
FroxelOptions parse_froxel_options(const nlohmann::json& j, const std::string& file);
nlohmann::json froxel_options_to_json(const FroxelOptions& options);

}  // namespace kiri::geometry
