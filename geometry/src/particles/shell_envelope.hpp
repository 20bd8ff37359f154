#pragma once
// Internal: the proposal of the particles' rejection sampler. Drawing uniformly in the Medium's
// whole box wastes most trials when the shell follows the terrain (a thin sheet in a tall box)
// and more when only a share of the shell is drawn (combined rendering's top band, under half
// the density). This envelope bounds the density per cell of the Medium's grid instead: a box
// from the lowest height where the share can be non-zero to the cell's highest top, at a bound of
// the density there. A point drawn uniformly under it and kept with probability q(p) / bound is
// distributed as q exactly (rejection sampling needs only q <= bound wherever q > 0).
#include <cstddef>
#include <functional>
#include <random>
#include <vector>

#include <glm/vec3.hpp>

#include "kiri/geometry/medium/medium.hpp"

namespace kiri::geometry::detail {

class ShellEnvelope {
public:
    //! The envelope of d(p) share(h) for a share that is zero at height fractions h <= `from` and
    //! at most `share_max` above (d, h: medium.hpp). Bilinear grids take their extremes over a cell
    //! at its corners, so the cell's corners bound its floor, band and top; the profile falls
    //! with h, the noise and the dissipation are at most 1. With `by_thickness`, a factor of the
    //! fog's thickness (top - floor) that never falls as it grows, the share is times it there:
    //! the thickness is bilinear over a cell too, so the factor at its thickest corner bounds it.
    ShellEnvelope(const Medium& medium, double from, double share_max,
                  const std::function<double(double)>& by_thickness = {});

    bool empty() const { return cells_.empty(); }
    //! The envelope's integral (m^3 of relative density): trials x this / hits estimates q's.
    double volume() const { return cumulative_.empty() ? 0.0 : cumulative_.back(); }

    struct Proposal {
        glm::dvec3 position{0.0};
        double bound = 0.0;  //!< the envelope there: keep the point with probability q / bound
    };
    //! A point uniform under the envelope (four numbers from `rng`). Requires !empty().
    Proposal draw(std::mt19937_64& rng) const;

private:
    struct Cell {
        double x = 0.0, y = 0.0, z_low = 0.0, height = 0.0, bound = 0.0;
    };
    std::vector<Cell> cells_;
    std::vector<double> cumulative_;  // the cells' integrals, summed
    double dx_ = 0.0, dy_ = 0.0;
};

//! Uniform in [0, 1) from the top 53 bits: the same numbers on every platform (the standard
//! distributions are implementation-defined).
inline double uniform(std::mt19937_64& rng) { return double(rng() >> 11) * 0x1.0p-53; }

}  // namespace kiri::geometry::detail
