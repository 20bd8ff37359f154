#pragma once
// Internal: the scene's "fog" section <-> JSON (nlohmann stays out of public headers).
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "kiri/geometry/scene/fog_spec.hpp"

namespace kiri::geometry {

//! Reads j (the value at `pointer`, e.g. "/fog"). Unknown keys are errors. Relative file names
//! in it (a fill's seed mask) are resolved against base_dir.
//! \throw InputError(file, "/fog/...", reason).
FogSpec parse_fog_spec(const nlohmann::json& j, const std::string& file, const std::string& pointer = "/fog",
                       const std::filesystem::path& base_dir = {});
nlohmann::json fog_spec_to_json(const FogSpec& spec);

}  // namespace kiri::geometry
