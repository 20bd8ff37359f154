#pragma once
//! \file scene_fog.hpp
//! A scene's fog, ready for the renderers and exporters: the fitted base surface (docs/fog.md)
//! and the layer stack's base and options in world units (docs/layers.md), and the medium they
//! describe.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "kiri/geometry/scene/fog_spec.hpp"
#include "kiri/geometry/layers/layer_stack.hpp"
#include "kiri/geometry/medium/medium.hpp"
#include "kiri/geometry/scene/scene.hpp"

namespace kiri::geometry {

struct SceneFog {
    AuthoredSurface authored;
    LayerOptions layers;  //!< world units (world_layer_options)
    LayerBase base;
    Medium medium;  //!< the same fog as a participating medium (medium.hpp), for every volume renderer
    double seconds_layer_base = 0.0, seconds_medium = 0.0;
    //! Fog placed by the terrain (docs/placement.md): what place_fog computed, for the maps and the
    //! report; the medium is then the fill's columns (fill_medium.hpp).
    std::optional<PlacedFog> placed;
};

//! Fits and tessellates the scene's fog over `terrain` (loaded with load_scene_terrain) and
//! prepares its layers. \throw InputError naming the scene file (no fog section, bad options).
SceneFog author_scene_fog(const Scene& scene, const Terrain& terrain);

//! report.json of `kiri author`: author_report_json's sections, then "optics" (the medium's
//! extinction, visibility, liquid water content, albedo, g, and the engines' equivalents,
//! engine_fog in medium.hpp) and, for fog placed by the terrain, "placement" (per
//! region, the fog, the valleys, the outline, flow, burn-off, timings). Heights and
//! thicknesses there are metres of the DEM (the exaggeration taken out).
//! seconds_load_terrain, when >= 0, joins the other stages' timings.
std::string scene_fog_report_json(const Scene& scene, const SceneFog& fog, double seconds_load_terrain = -1.0);

//! The optics as (name, value) pairs for the metadata of exported maps.
std::vector<std::pair<std::string, std::string>> optics_metadata(const MediumOptions& medium);

}  // namespace kiri::geometry
