#pragma once
//! \file fill_medium.hpp
//! The Medium (medium.hpp) of fog placed by the terrain (issue 10): the fill's columns as the
//! shell, so the volume renderers draw the fog the terrain holds, not the fitted lake surface.
#include <string>

#include "kiri/geometry/fog_placement.hpp"
#include "kiri/geometry/medium.hpp"

namespace kiri::geometry {

//! Shell on the terrain's grid (every s-th sample, s chosen so the spacing is at least
//! options.grid_spacing and a side has at most options.max_grid_side samples): top = the fog's
//! top, floor = its bottom above the ground (a lifted base included), bottom = the density
//! profile's h = 0 (placed.medium_bottom: the region's lowest bottom for the "fill" profile, the
//! column's own for "blanket"), coverage 1 over fog, 0 elsewhere. Without fog a cell's shell
//! is flat on the ground. \throw InputError(label, "/medium/...") on bad options.
Medium fill_medium(const Terrain& terrain, const PlacedFog& placed, const MediumOptions& options,
                   const MediumDetail& detail, const std::string& label = {});

//! Parameters of the same fog in the engines users take it to (docs/placement.md): HDRP's fog
//! attenuation distance (the mean free path 1 / sigma, metres), Unreal's Exponential Height
//! Fog density (it divides by 1000, works in centimetres and integrates with exp2, so
//! FogDensity = sigma / (0.1 (ln 2)^2) at zero height falloff), Godot's fog and volumetric fog
//! density (an extinction per metre: sigma).
struct EngineFog {
    double hdrp_attenuation_distance_m = 0.0;
    double unreal_fog_density = 0.0;
    double godot_density = 0.0;
};
EngineFog engine_fog(double extinction);

}  // namespace kiri::geometry
