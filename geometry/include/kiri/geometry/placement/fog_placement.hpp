#pragma once
//! \file fog_placement.hpp
//! Fog placed by the terrain, the scene's side: fill regions (seeds + fog top),
//! automatic seeding, burn-off and flow, and the one call that turns them into fog columns, a
//! footprint and a lake target for the existing fit and layers.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "kiri/geometry/core/fields.hpp"
#include "kiri/geometry/placement/burn_off.hpp"
#include "kiri/geometry/placement/fog_columns.hpp"
#include "kiri/geometry/placement/fog_fill.hpp"
#include "kiri/geometry/placement/fog_flow.hpp"
#include "kiri/geometry/placement/mask_outline.hpp"
#include "kiri/geometry/terrain/terrain.hpp"
#include "kiri/geometry/placement/valley_analysis.hpp"

namespace kiri::geometry {

enum class SeedKind {
    points,   //!< FillRegionSpec::points
    all,      //!< every basin below the top
    valleys,  //!< the valley analysis' mask (automatic seeding)
    mask,     //!< a mask raster the user gave (FillRegionSpec::mask_path)
};

//! One fill region of the scene ("fog": {"fill": {...}} or an array of them; regions may
//! overlap). Heights in the heightfield's units (world metres once world_fog_spec scaled them).
struct FillRegionSpec {
    double top = 0.0;
    SeedKind seeds = SeedKind::points;
    std::vector<glm::dvec2> points;
    std::filesystem::path mask_path;
    ValleyOptions valleys;
    double min_thickness = 0.0;
    double max_thickness = 0.0;  //!< 0 = no limit
    //! The medium's density profile over this region's fog, from 0 (blanket: relative to each
    //! column, densest at the column's own bottom) to 1 (fill: by absolute altitude, densest at
    //! the region's lowest bottom, the same at a given altitude across the region).
    double profile = 1.0;
    bool operator==(const FillRegionSpec&) const = default;
};

//! The "fill" object of the scene's "fog" section (or each of an array of them). max_thickness is
//! 0 or above min_thickness; "valleys" goes with "seeds": "valleys" only.
template <fields_of<FillRegionSpec> O, class V>
void visit_fields(O& o, V&& v)
{
    v(o.top,
      {.key = "top",
       .unit = "m",
       .doc = "the fog-top altitude (the inversion), metres of the DEM",
       .shown_default = "derived: 30 % of the land below it, at least a fifth of the relief deep"});
    v(hand_written,
      {.key = "seeds",
       .doc = "`[[x, y], ...]` seed points (local metres); `\"all\"` every basin below the top; "
              "`\"valleys\"` automatic seeding; `{\"mask\": FILE}` a raster of the DEM's size (relative "
              "to the scene), nonzero pixels seed, north up when it has no geotransform",
       .shown_default = "required",
       .type = "points, `\"all\"`, `\"valleys\"` or `{\"mask\": FILE}`"});
    v(hand_written,
      {.key = "valleys",
       .doc = "with `\"seeds\": \"valleys\"` only: the valley analysis (the table below)",
       .type = "object"});
    v(o.min_thickness,
      {.key = "min_thickness",
       .unit = "m",
       .range = at_least(0),
       .doc = "fog lies, and the flood passes, only where top - ground > this",
       .widget = closed(0, 200)});
    v(o.max_thickness,
      {.key = "max_thickness",
       .unit = "m",
       .range = at_least(0),
       .doc = "0 = down to the ground; otherwise the fog's bottom is max(ground, top - this)",
       .widget = closed(1, 2000),
       .log_widget = true});
    v(o.profile,
      {.key = "profile",
       .range = closed(0, 1),
       .doc = "density profile: 0 blanket (height above the column's ground), 1 fill (absolute "
              "altitude), between: blended"});
}

struct PlacementSpec {
    std::vector<FillRegionSpec> regions;  //!< at least one
    //! Footprint outline (mask_outline.hpp); margin < 0 = one patch size, tolerance 0 = a
    //! quarter of the patch size.
    double margin = -1.0;
    double tolerance = 0.0;
    double min_area = 0.0;
    std::optional<FlowOptions> flow;         //!< applied first (the night's wind)
    bool evaporation_given = false;          //!< flow.evaporation_depth from the scene, not the medium
    std::optional<BurnOffOptions> burn_off;  //!< then the morning's sun
    bool latitude_given = false;             //!< burn_off.latitude from the scene, not the DEM
    double exaggeration = 1.0;               //!< heights are stretched by this (for messages)
    bool operator==(const PlacementSpec&) const = default;
};

//! The "outline" object of the scene's "fog" section: the placement's own fields.
template <fields_of<PlacementSpec> O, class V>
void visit_outline_fields(O& o, V&& v)
{
    v(o.margin,
      {.key = "margin",
       .unit = "m",
       .range = closed(0, 1e6),
       .doc = "the footprint extends past the fog cells (into cells the fit may use)",
       .shown_default = "one `patch_size`",
       .omit_default = true});
    v(o.tolerance,
      {.key = "tolerance",
       .unit = "m",
       .range = closed(0, 1e6),
       .doc = "Douglas-Peucker tolerance of the polygons",
       .shown_default = "a quarter of `patch_size`"});
    v(o.min_area,
      {.key = "min_area", .unit = "m^2", .range = at_least(0), .doc = "fog bodies under this area get no polygon"});
}
struct OutlineFields {
    template <class O, class V>
    void operator()(O& o, V&& v) const
    {
        visit_outline_fields(o, v);
    }
};

//! Metres of descent that evaporate all but 1/e of fog of extinction sigma (1/m): its liquid
//! water content, LWC = sigma 4 rho_w r / (3 Q) with r = 7 um and Q = 2 (medium.hpp), divided by
//! what warming at the dry adiabatic 9.8 K/km evaporates, 0.45 g/m^3 per K near 5 C (the slope
//! of the saturation vapour density): 21 m for sigma = 0.02 1/m.
double evaporation_depth_for(double extinction);

//! What place_fog computed, kept for the maps and the report.
struct PlacedFog {
    FogColumns columns;  //!< the fog after flow and burn-off
    ColumnFigures figures;
    std::vector<FogFill> fills;        //!< per region, as filled
    std::optional<ValleyMap> valleys;  //!< of the first region seeded by valleys
    std::optional<FloodLevels> flood;  //!< of the first region seeded by points
    std::optional<FlowReport> flow;
    std::optional<BurnOffReport> burn_off;
    double latitude = 0.0;  //!< used by the burn-off
    MaskOutline outline;
    //! The top is one flat altitude (fit: lake at `top`); otherwise `top_grid` is the lake
    //! target: the fog's top where there is fog, just under the ground elsewhere.
    bool flat = true;
    double top = 0.0;
    std::shared_ptr<const Heightfield> top_grid;
    //! The medium's bottom per cell (blend of each region's profile, see FillRegionSpec::profile);
    //! the ground where there is no fog.
    std::vector<double> medium_bottom;
    double seconds_fill = 0.0, seconds_valleys = 0.0, seconds_flood_levels = 0.0, seconds_flow = 0.0,
           seconds_burn_off = 0.0, seconds_outline = 0.0;
};

//! Fills every region, merges them, lets the flow and the burn-off act, and outlines the fog.
//! `patch_size` sets the outline's defaults. Errors name "/fog/fill[/K]/<key>",
//! "/fog/flow/<key>", "/fog/burn_off/<key>" with label as the file.
PlacedFog place_fog(const Terrain& terrain, const PlacementSpec& spec, double patch_size,
                    const std::string& label = {});

//! The latitude (degrees) of the terrain's centre when its source raster has a CRS GDAL can
//! transform to WGS 84; `fallback` otherwise.
double terrain_latitude(const Heightfield& terrain, double fallback);

}  // namespace kiri::geometry
