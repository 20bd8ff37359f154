#pragma once
//! \file fog_fill.hpp
//! Fog placed by the terrain: valley fill from seeds up to a flat fog top (the
//! temperature inversion, [ValleyFog]), by priority-flood over the DEM ([Barnes14]).
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "kiri/geometry/terrain/heightfield.hpp"

namespace kiri::geometry {

//! Where the fill starts. Seeds below the top start the flood; seeds at or above it are
//! skipped (a seed high on a ridge has no fog under an inversion below it).
struct FillSeeds {
    std::vector<glm::dvec2> points;  //!< local metres (x east, y north), each must lie on the terrain
    //! nx * ny flags in the heightfield's order (j * nx + i), nonzero = seed cell (automatic
    //! seeding, or a mask the user edited); empty = none.
    std::vector<std::uint8_t> mask;
    //! Every cell below the top is fog: every basin reaching below the inversion is seeded
    //! (points and mask are then ignored).
    bool all_basins = false;
    bool operator==(const FillSeeds&) const = default;
};

struct FillOptions {
    double top = 0.0;  //!< fog-top altitude (metres, the heightfield's heights)
    FillSeeds seeds;
    //! The flood passes, and fog lies, only where top - ground > min_thickness (metres, >= 0):
    //! a thinner sheet neither counts as fog nor carries it over a saddle.
    double min_thickness = 0.0;
    //! The fog's bottom is max(ground, top - max_thickness): over deeper ground the fog hangs
    //! as a layer of this thickness (metres; 0 = no limit, always down to the ground).
    double max_thickness = 0.0;
    //! Heights in error messages are divided by this (a scene's vertical exaggeration, by which
    //! its heights were stretched), so they read in the metres the user wrote.
    double message_scale = 1.0;
    bool operator==(const FillOptions&) const = default;
};

//! The fog of a fill. Cell k = j * nx + i is fog when mask[k] = 1; its column spans
//! [top - thickness[k], top]. Nodata cells (Heightfield::valid = 0) are never fog and stop
//! the flood (kiri knows nothing of the ground there); the grid's border stops it too.
struct FogFill {
    int nx = 0, ny = 0;
    double top = 0.0;
    std::vector<std::uint8_t> mask;
    std::vector<double> thickness;  //!< metres; 0 where there is no fog
    std::size_t cells = 0;          //!< fog cells
    double area_m2 = 0.0;           //!< cells * dx * dy
    double volume_m3 = 0.0;         //!< sum of thickness * dx * dy
    double max_thickness = 0.0, mean_thickness = 0.0;
    //! Whether a higher top would spill over a saddle into another basin below the top (not
    //! yet fogged); then spill_level is the lowest such top (the saddle's ground, plus
    //! min_thickness) and spill_point the saddle. Never with all_basins.
    bool spills = false;
    double spill_level = 0.0;
    glm::dvec2 spill_point{0.0};
    bool touches_border = false;  //!< fog reaches the grid's edge (it would go on beyond the DEM)
    int seed_cells = 0;           //!< seed cells below the top (that started the flood)
};

//! Cells below `top` connected to a seed through cells below `top` (8-neighbours), with the
//! thickness per cell = top - max(ground, top - max_thickness). A top above a saddle spills into
//! the next basin, a top at or below it does not. The region is a linear-time breadth-first
//! search; the spill search beyond it is a priority-flood over the cells above the top up to the
//! spill level, O(n log n) worst case (a radix heap keyed by the flood level: each cell enters
//! and leaves it once; n = the cells visited).
//! \throw InputError(label, field, reason): "seeds/K" outside the terrain or on nodata, "top"
//!        below every seed, "min_thickness" / "max_thickness" out of range, "seeds/mask" of the
//!        wrong size; fields are relative (the scene reader prefixes its JSON pointer).
FogFill fill_fog(const Heightfield& terrain, const FillOptions& options, const std::string& label = {});

//! For every cell, the lowest fog top at which the seeds' fog reaches it: the minimax ground
//! height over all 8-connected paths from a seed (the seed's own ground for a seed cell).
struct FloodLevels {
    std::vector<double> level;          //!< metres; 0 where not reached
    std::vector<std::uint8_t> reached;  //!< 0 where no path exists (walled in by nodata)
};
//! Priority-flood from the seeds without a top (the whole grid). With all_basins the level is
//! the ground itself. Same errors as fill_fog (the top is not used).
FloodLevels flood_levels(const Heightfield& terrain, const FillSeeds& seeds, const std::string& label = {});

//! The seed cells of `seeds` on this grid (index j * nx + i), in order, duplicates removed.
//! \throw InputError as fill_fog.
std::vector<std::uint32_t> seed_cells(const Heightfield& terrain, const FillSeeds& seeds,
                                      const std::string& label = {});

}  // namespace kiri::geometry
