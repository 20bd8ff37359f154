#pragma once
// Internal: the particles' positions evened out across the fog after the sample elimination.
// Blue noise still crowds and thins out from place to place, and a fog one particle deep (the
// default blanket) shows that as blotches of denser and thinner fog the size of a particle:
// most of the particles' error against the reference (docs/particles.md, "Evened out"). A few
// sweeps of pairwise repulsion ([Turk92]'s relaxation, in each point's local spacing) bring
// the arrangement towards a lattice's.
#include <cstddef>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

#include "kiri/geometry/medium/medium.hpp"

namespace kiri::geometry::detail {

struct RelaxFog {
    std::function<double(const glm::dvec3&)> spacing;    //!< the local spacing at a point (> 0)
    std::function<double(const glm::dvec3&)> density;    //!< > 0 inside the fog the points stand for
    std::function<MediumColumn(double, double)> column;  //!< the fog's floor and top at (x, y)
};

//! `iterations` Jacobi sweeps: each point moves across the fog, in (x, y), away from the points
//! nearer than `reach` times the mean of the two's local spacings (the push of each falls as
//! (1 - d / r)^2), by a quarter of the summed push and at most 0.15 of its spacing a sweep; its
//! height keeps its share of its column between floor and top, so a blanket's points stay as
//! high within it wherever they move. A point with no fog in some column within its reach (the
//! fog's edge) stays where it is, and pushes the others: a free edge would drift outwards. A move
//! that would leave the fog (density 0, or a column without fog) is not made. Deterministic on any
//! number of threads.
void relax_points(std::vector<glm::dvec3>& points, const RelaxFog& fog, int iterations, double reach);

}  // namespace kiri::geometry::detail
