#pragma once
// Internal: the scene's "layers" section <-> JSON.
#include <string>

#include <nlohmann/json.hpp>

#include "kiri/geometry/layers/layer_stack.hpp"

namespace kiri::geometry {

//! \throw InputError(file, "/layers/...", reason); unknown keys are errors.
LayerOptions parse_layer_options(const nlohmann::json& j, const std::string& file);
nlohmann::json layer_options_to_json(const LayerOptions& options);

}  // namespace kiri::geometry
