#pragma once
// Internal: sample elimination ([Yuksel15]), with distances measured in units of each point's
// local spacing so that a candidate set drawn with a varying density keeps that density while
// becoming blue noise.
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

namespace kiri::geometry::detail {

//! Keeps `target` of the points: repeatedly removes the point with the largest weight
//! sum_j (1 - d_ij / (2 r_ij))^8, r_ij = 0.561 (h_i + h_j) / 2 (Yuksel's r_max for spacing h in 3D),
//! with Yuksel's weight limiting. `spacing` is h per point (> 0), `cell` a lower bound of every h
//! (the neighbour grid's cell). Returns the indices kept, ascending. Deterministic.
std::vector<std::size_t> eliminate_samples(const std::vector<glm::dvec3>& points, const std::vector<double>& spacing,
                                           double cell, std::size_t target);

}  // namespace kiri::geometry::detail
