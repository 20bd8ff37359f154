#pragma once
// Internal: where a ray is inside the Medium's shell (floor <= z <= top), exactly. In a grid
// cell every grid is bilinear in (x, y), so along a ray each is a quadratic in t: the shell's
// floor and top crossings are roots of quadratics, and between them the density is smooth.
#include <vector>

#include <glm/vec3.hpp>

#include "kiri/geometry/medium/medium.hpp"

namespace kiri::geometry::detail {

struct Interval {
    double t0 = 0.0, t1 = 0.0;
};

//! Appends to `out` (cleared first) the disjoint, sorted intervals of [t0, t1] where o + t d
//! lies in the shell over a cell with some coverage. d need not be unit.
void shell_intervals(const Medium& medium, const glm::dvec3& o, const glm::dvec3& d, double t0, double t1,
                     std::vector<Interval>& out);

}  // namespace kiri::geometry::detail
