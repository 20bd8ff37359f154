#pragma once
// Internal: exact ray queries on a heightfield triangulated like geometry::Terrain (two
// triangles per cell, split along (i, j)-(i + 1, j + 1)); no mesh, no AABB tree, thread-safe.
#include <optional>

#include <glm/vec3.hpp>

#include "kiri/geometry/terrain/heightfield.hpp"
#include "reference/grid_walk.hpp"

namespace kiri::geometry::detail {

class HeightfieldRay {
public:
    explicit HeightfieldRay(const Heightfield& hf);
    //! The smallest t in [t0, t1] where o + t d is on or under the terrain (d need not be unit);
    //! empty when the ray stays above it or leaves the grid first. A ray from outside the grid
    //! entering it under the edge hits only after coming out above the surface (no walls).
    std::optional<double> first_hit(const glm::dvec3& o, const glm::dvec3& d, double t0, double t1) const;
    //! Unit normal of the triangle under (x, y) (z >= 0).
    glm::dvec3 normal(double x, double y) const;
    double z_min() const { return z_min_; }
    double z_max() const { return z_max_; }

private:
    const Heightfield& hf_;
    GridFrame frame_;
    double z_min_ = 0.0, z_max_ = 0.0;
    // Terrain height in cell (i, j) at cell coordinates (s, r) in [0, 1]^2.
    double cell_height(int i, int j, double s, double r) const;
};

}  // namespace kiri::geometry::detail
