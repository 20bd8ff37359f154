#pragma once
//! \file valley_analysis.hpp
//! Candidate fog regions found from the terrain ("automatic seeding"): a multi-scale
//! topographic position index ([Weiss01], [Guisan99]) as a cold-air-pool index, with
//! one threshold. Cold air drains into whatever lies low against its surroundings, at the
//! scale of gullies as well as of whole valleys ([ValleyFog]).
#include <cstdint>
#include <string>
#include <vector>

#include "kiri/geometry/core/fields.hpp"
#include "kiri/geometry/terrain/heightfield.hpp"

namespace kiri::geometry {

struct ValleyOptions {
    //! Neighbourhood radii (metres): the TPI at radius r is ground - (ground smoothed by a
    //! Gaussian of sigma r). Empty = three radii, 4, 16 and 64 cells (of the larger side),
    //! each at most a quarter of the terrain's smaller extent.
    std::vector<double> radii;
    //! The one parameter: a cell is a candidate where its index exceeds this (standard
    //! deviations below its surroundings, averaged over the radii). 1 keeps valley floors.
    double threshold = 1.0;
    bool operator==(const ValleyOptions&) const = default;
};

//! The "valleys" object of a fill region (fog_placement.hpp).
template <fields_of<ValleyOptions> O, class V>
void visit_fields(O& o, V&& v)
{
    v(o.threshold,
      {.key = "threshold",
       .range = closed(-10, 10),
       .doc = "standard deviations of the cold-air-pool index: a cell is a candidate above it",
       .widget = closed(-2, 4)});
    v(hand_written,
      {.key = "radii",
       .unit = "m",
       .range = open_range(0, 1e7),
       .doc = "1 to 8 radii of the index (default 4, 16 and 64 cells, each at most a quarter of the "
              "smaller extent)",
       .shown_default = "automatic",
       .type = "[r, ...]"});
}

struct ValleyMap {
    int nx = 0, ny = 0;
    //! Cold-air-pool index per cell: minus the mean over the radii of the TPI divided by its
    //! standard deviation over the terrain. Dimensionless, > 0 in hollows, 0 on nodata cells;
    //! unchanged by any scale and offset of the heights (the vertical exaggeration included).
    std::vector<double> index;
    std::vector<std::uint8_t> mask;  //!< index > threshold, on valid cells
    std::vector<double> radii;       //!< the radii used (metres)
    std::size_t cells = 0;           //!< candidate cells
};

//! \throw InputError(label, "valleys/...", reason) for radii <= 0 or not finite, a threshold
//!        that is not finite.
ValleyMap analyse_valleys(const Heightfield& terrain, const ValleyOptions& options, const std::string& label = {});

}  // namespace kiri::geometry
