#pragma once
//! \file fog_spec.hpp
//! The scene's "fog" section (docs/scene.md): footprint, surface kind, fit and tessellation,
//! and the one call that turns it into a base surface (what `kiri author` writes).
#include <optional>
#include <string>

#include "kiri/geometry/fog/base_surface.hpp"
#include "kiri/geometry/placement/fog_placement.hpp"
#include "kiri/geometry/fog/footprint.hpp"
#include "kiri/geometry/fog/tessellate.hpp"

namespace kiri::geometry {

struct FogSpec {
    //! Footprint in local metres; empty polygon = the terrain's extent shrunk by `margin`.
    Footprint footprint;
    double margin = 0.0;  //!< metres, for the whole-terrain footprint
    SurfaceKind surface = SurfaceKind::catmull_clark;
    double patch_size = 1000.0;
    FitOptions fit;
    TessellationOptions tessellation;
    //! Fog placed by the terrain ("fill", "outline", "flow", "burn_off"; fog_placement.hpp):
    //! the footprint and the lake target come from place_fog (placed_fog_spec). The stages
    //! below place it themselves while `footprint` is empty.
    std::optional<PlacementSpec> placement;
    bool operator==(const FogSpec&) const = default;
};

//! spec with the placed fog's footprint and lake target: mode lake at the flat top (or over
//! placed.top_grid), thickness the fog's greatest (at least 1 m).
FogSpec placed_fog_spec(const FogSpec& spec, const PlacedFog& placed);

// The fog's surface stages (the Pipeline, pipeline.hpp, runs them in order and keeps each
// product until its inputs change).

//! The spec's footprint polygon, or the terrain's extent less the margin when it has none.
//! \throw InputError(label, "/fog/margin") when the margin leaves nothing.
Footprint fog_footprint(const Terrain& terrain, const FogSpec& spec, const std::string& label = {});
//! Footprint -> control mesh (heights from the terrain) -> surface of spec.surface, not fitted.
BaseSurface fog_control_surface(const Terrain& terrain, const FogSpec& spec, const std::string& label = {});
//! surface.fit(terrain, spec.fit) with errors named "/fog/<key>" and label as the file.
FitReport fit_fog_surface(BaseSurface& surface, const Terrain& terrain, const FogSpec& spec,
                          const std::string& label = {});

}  // namespace kiri::geometry
