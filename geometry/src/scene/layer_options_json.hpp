#pragma once
// Internal: the scene's "layers" section <-> JSON.
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "kiri/geometry/layers/layer_stack.hpp"

namespace kiri::geometry {

//! medium_keys: the medium's keys the section may give under their old names (read by the
//! medium's reader). \throw InputError(file, "/layers/...", reason); other unknown keys are errors.
LayerOptions parse_layer_options(const nlohmann::json& j, const std::string& file,
                                 const std::set<std::string>& medium_keys = {});
nlohmann::json layer_options_to_json(const LayerOptions& options);

}  // namespace kiri::geometry
