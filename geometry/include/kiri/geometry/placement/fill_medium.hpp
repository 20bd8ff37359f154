#pragma once
//! \file fill_medium.hpp
//! The Medium (medium.hpp) of fog placed by the terrain: the fill's columns as the
//! shell, so the volume renderers draw the fog the terrain holds, not the fitted lake surface.
#include <string>

#include "kiri/geometry/placement/fog_placement.hpp"
#include "kiri/geometry/medium/medium.hpp"

namespace kiri::geometry {

//! Shell on the terrain's grid over the fog's bounds (every s-th sample, from a sample before the
//! fog's columns to one after them; s chosen so the spacing is at least options.grid_spacing and
//! a side has at most options.max_grid_side samples over those bounds): top = the fog's
//! top, floor = its bottom above the ground (a lifted base included), bottom = the density
//! profile's h = 0 (placed.medium_bottom: the region's lowest bottom for the "fill" profile, the
//! column's own for "blanket"), coverage 1 over fog, 0 elsewhere. Without fog a cell's shell
//! is flat on the ground. \throw InputError(label, "/medium/...") on bad options.
Medium fill_medium(const Terrain& terrain, const PlacedFog& placed, const MediumOptions& options,
                   const MediumDetail& detail, const std::string& label = {});

}  // namespace kiri::geometry
