#pragma once
// The scene's "combined" section (docs/scene.md): FogPartition.
#include <string>

#include <nlohmann/json.hpp>

#include "kiri/geometry/medium/fog_partition.hpp"

namespace kiri::geometry {

FogPartition parse_fog_partition(const nlohmann::json& j, const std::string& file);
nlohmann::json fog_partition_to_json(const FogPartition& p);

}  // namespace kiri::geometry
