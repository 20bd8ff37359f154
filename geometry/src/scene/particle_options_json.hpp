#pragma once
// Internal: the scene's "particles" section <-> JSON (docs/particles.md).
#include <string>

#include <nlohmann/json.hpp>

#include "kiri/geometry/particles/particles.hpp"

namespace kiri::geometry {

//! \throw InputError(file, "/particles/...", reason); unknown keys are errors.
ParticleOptions parse_particle_options(const nlohmann::json& j, const std::string& file);
nlohmann::json particle_options_to_json(const ParticleOptions& options);

}  // namespace kiri::geometry
