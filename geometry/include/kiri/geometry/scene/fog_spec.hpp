#pragma once
//! \file fog_spec.hpp
//! The scene's "fog" section (docs/scene.md): footprint, surface kind, fit and tessellation,
//! and the one call that turns it into a base surface (what `kiri author` writes).
#include <optional>
#include <string>

#include "kiri/geometry/core/fields.hpp"
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

inline constexpr Choice surface_kind_names[] = {{"gregory", int(SurfaceKind::gregory)},
                                                {"catmull-clark", int(SurfaceKind::catmull_clark)}};

//! The "fog" section: the base surface, its fit (FitOptions) and tessellation, or fog placed by
//! the terrain (fill, outline, flow, burn_off), which sets the footprint and the fit's mode,
//! altitude and thickness itself.
template <fields_of<FogSpec> O, class V>
void visit_fields(O& o, V&& v)
{
    v(hand_written,
      {.key = "footprint",
       .doc = "where the fog lies, seen from above, in local metres (x east, y north, origin near the DEM's centre): "
              "`{\"type\": \"terrain\", \"margin\": M}` the DEM's extent less M metres on every side; "
              "`{\"type\": \"rectangle\", \"min\": [x, y], \"max\": [x, y]}`; `{\"type\": \"polygon\", \"points\": "
              "[[x, y], ...]}` a simple polygon (either orientation, not closed, no crossing or touching edges). The "
              "footprint must lie inside the terrain: kiri does not clip it.",
       .shown_default = "`{\"type\": \"terrain\", \"margin\": 0}`",
       .type = "object"});
    v(o.surface,
      {.key = "surface",
       .doc = "`gregory` (G1 network of bicubic Gregory patches, LSNC 2009) or `catmull-clark` (OpenSubdiv "
              "limit surface)",
       .choices = surface_kind_names});
    v(o.patch_size,
      {.key = "patch_size",
       .unit = "m",
       .range = greater_than(0),
       .doc = "control-mesh cell size: one patch per cell",
       .widget = closed(100, 10000),
       .log_widget = true});
    visit_fields(o.fit, v);
    v(hand_written,
      {.key = "tessellation",
       .doc = "`level`, or `tolerance` and `max_level` (the table below)",
       .shown_default = "`{\"level\": 8}`",
       .type = "object"});
    v(hand_written,
      {.key = "fill",
       .doc = "fog placed by the terrain: seeds and a fog top ([placement.md](placement.md#scene-keys))",
       .type = "object or array"});
    v(hand_written, {.key = "outline", .doc = "with `fill`: the footprint's outline", .type = "object"});
    v(hand_written, {.key = "flow", .doc = "with `fill`: the night's wind over the passes", .type = "object"});
    v(hand_written, {.key = "burn_off", .doc = "with `fill`: the morning's sun", .type = "object"});
}

//! The footprint {"type": "terrain"}'s own key.
template <fields_of<FogSpec> O, class V>
void visit_terrain_footprint_fields(O& o, V&& v)
{
    v(o.margin,
      {.key = "margin",
       .unit = "m",
       .range = at_least(0),
       .doc = "the terrain's extent less this on every side",
       .widget = closed(0, 10000)});
}
struct TerrainFootprintFields {
    template <class O, class V>
    void operator()(O& o, V&& v) const
    {
        visit_terrain_footprint_fields(o, v);
    }
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
