#pragma once
//! \file fog_columns.hpp
//! Fog as a column over each terrain cell: the "fill" density profile (absolute
//! altitudes), which the Medium, the maps and the renderers' targets read.
#include <cstdint>
#include <vector>

#include "kiri/geometry/placement/fog_fill.hpp"
#include "kiri/geometry/terrain/heightfield.hpp"

namespace kiri::geometry {

//! Cell k = j * nx + i of the terrain's grid holds fog from bottom[k] up to top[k] (metres,
//! absolute, the heightfield's heights) where mask[k] = 1; elsewhere bottom = top = the ground.
struct FogColumns {
    int nx = 0, ny = 0;
    std::vector<std::uint8_t> mask;
    std::vector<double> bottom, top;

    double thickness(std::size_t k) const { return mask[k] ? top[k] - bottom[k] : 0.0; }
};

//! The columns of one fill: top flat at fill.top, bottom top - thickness.
FogColumns fill_columns(const Heightfield& terrain, const FogFill& fill);

//! Union of two column sets on the same grid (regions may overlap): where both have fog the
//! column spans from the lower bottom to the higher top.
FogColumns merge_columns(const FogColumns& a, const FogColumns& b);

//! Figures of a column set: fog cells, area (m^2), volume (m^3), thickness extremes (m) and
//! the range of the tops and bottoms over the fog (0 when there is none).
struct ColumnFigures {
    std::size_t cells = 0;
    double area_m2 = 0.0, volume_m3 = 0.0;
    double max_thickness = 0.0, mean_thickness = 0.0;
    double top_min = 0.0, top_max = 0.0, bottom_min = 0.0, bottom_max = 0.0;
};
ColumnFigures column_figures(const Heightfield& terrain, const FogColumns& columns);

}  // namespace kiri::geometry
