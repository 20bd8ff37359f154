#pragma once
//! \file mask_outline.hpp
//! A cell mask on the terrain's grid (a fill's fog cells, a valley mask) turned into footprint
//! polygons, so the existing control mesh, fit and layers follow it.
#include <cstdint>
#include <string>
#include <vector>

#include "kiri/geometry/fog/footprint.hpp"
#include "kiri/geometry/terrain/heightfield.hpp"

namespace kiri::geometry {

struct OutlineOptions {
    //! Metres the mask first grows into the cells marked `growable` (ground the fog top passes
    //! under: the lake surface there is hidden by the terrain, so a wider footprint costs
    //! nothing and keeps narrow valleys wider than a patch). 0 = no growth.
    double margin = 0.0;
    //! Douglas-Peucker tolerance (metres) of the outlines; 0 = half the smaller cell side.
    //! Halved, down to the raw outline, where simplifying would make polygons touch, leave a
    //! cell of the mask out or take in a cell neither in the mask nor growable.
    double tolerance = 0.0;
    //! Components (4-connected, after growing) of less area (m^2) are dropped.
    double min_area = 0.0;
    bool operator==(const OutlineOptions&) const = default;
};

struct MaskOutline {
    Footprint footprint;       //!< polygon + more: the outer border of each component kept
    int components = 0;        //!< kept (nested ones, inside another's hole, are covered by it)
    int dropped = 0;           //!< below min_area
    double tolerance = 0.0;    //!< the Douglas-Peucker tolerance used (metres)
    std::size_t vertices = 0;  //!< over all polygons
};

//! Outlines the cells of `mask` (nx * ny flags, j * nx + i; each sample stands for the dx x dy
//! cell around it) as simple, disjoint polygons inside the terrain's extent: grows the mask by
//! margin into `growable` (same size, or empty = nowhere), closes diagonal-only contacts
//! (which would pinch a polygon), traces each 4-connected component's outer border along cell
//! edges, clamps it to the grid's extent and simplifies it. Holes are left out: the footprint
//! covers them (for a fill they are islands of ground above the top, which rise through a lake
//! surface anyway). O(cells + V^2) for V outline vertices.
//! \throw InputError(label, "mask", reason) for a mask of the wrong size or with no cell.
MaskOutline mask_outline(const Heightfield& grid, std::vector<std::uint8_t> mask,
                         const std::vector<std::uint8_t>& growable, const OutlineOptions& options,
                         const std::string& label = {});

}  // namespace kiri::geometry
