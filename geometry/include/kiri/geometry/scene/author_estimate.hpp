#pragma once
//! \file author_estimate.hpp
//! What authoring a scene's fog will need in memory, estimated from the scene before anything
//! large is allocated (docs/hardening.md): `kiri author` prints it, and a scene above the limit is refused
//! with the memory it would need and the key that drives it.
#include <string>

#include "kiri/geometry/scene/fog_spec.hpp"
#include "kiri/geometry/terrain/heightfield.hpp"

namespace kiri::geometry {

struct AuthorEstimate {
    double patches = 0.0;                //!< upper bound: cells of the footprint's bounding box
    double samples = 0.0;                //!< fit samples: terrain vertices under the fog + per patch
    double tessellation_vertices = 0.0;  //!< patches x (level + 1)^2 (the finest level if adaptive)
    double layer_vertices = 0.0;         //!< tessellation vertices x (layers + 1)
    double terrain_mib = 0.0, fit_mib = 0.0, tessellation_mib = 0.0, layers_mib = 0.0;
    double total_mib() const { return terrain_mib + fit_mib + tessellation_mib + layers_mib; }
    //! "about 412 MiB (terrain 53, fit 21, tessellation 26, layers 312)"
    std::string summary() const;
};

//! Refuse to author above this (MiB); documented in docs/hardening.md.
inline constexpr double author_memory_limit_mib = 16.0 * 1024.0;

//! `layers` is the number of layers above the base that will be built (exports).
AuthorEstimate estimate_author(const FogSpec& spec, const Heightfield& terrain, int layers);

//! \throw LimitError(label, key of the largest part, "... would need about N MiB ...; the limit
//!        is 16384 MiB") when the estimate is above author_memory_limit_mib.
void check_author_estimate(const AuthorEstimate& estimate, const std::string& label);

}  // namespace kiri::geometry
