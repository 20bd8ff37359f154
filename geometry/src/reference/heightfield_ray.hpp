#pragma once
// Internal: exact ray queries on the Ground (kiri/geometry/terrain/ground.hpp): the heightfield
// triangulated like geometry::Terrain (two triangles per cell, split along (i, j)-(i + 1, j + 1)),
// the sea's surface over its sea and the surround beyond its edge; no mesh, no AABB tree,
// thread-safe.
#include <optional>

#include <glm/vec3.hpp>

#include "kiri/geometry/terrain/ground.hpp"
#include "kiri/geometry/terrain/heightfield.hpp"
#include "reference/grid_walk.hpp"

namespace kiri::geometry::detail {

class HeightfieldRay {
public:
    explicit HeightfieldRay(const Heightfield& hf, bool surround = true);
    //! The smallest t in [t0, t1] where o + t d is on or under the ground (d need not be unit);
    //! empty when the ray stays above it. Without the surround, a ray leaving the grid meets
    //! nothing more, and one from outside entering the grid under the edge hits only after
    //! coming out above the surface (no walls).
    std::optional<double> first_hit(const glm::dvec3& o, const glm::dvec3& d, double t0, double t1) const;
    //! Unit normal of the ground under (x, y) (z >= 0).
    glm::dvec3 normal(double x, double y) const { return ground_.normal(x, y); }
    const Ground& ground() const { return ground_; }
    //! The grid's heights (the colours' range: the surround lies between them and its base).
    double z_min() const { return ground_.z_min(); }
    double z_max() const { return ground_.z_max(); }

private:
    const Heightfield& hf_;
    Ground ground_;
    GridFrame frame_;
    double top_ = 0.0;  // the highest the ground reaches, surround included
    // Ground height in cell (i, j) at cell coordinates (s, r) in [0, 1]^2.
    double cell_height(int i, int j, double s, double r) const;
    // The grid alone, for t in [t0, t1] inside its footprint.
    std::optional<double> grid_hit(const glm::dvec3& o, const glm::dvec3& d, double t0, double t1,
                                   bool under_at_entry) const;
    // The surround alone, for t in [t0, t1] outside the grid's footprint.
    std::optional<double> surround_hit(const glm::dvec3& o, const glm::dvec3& d, double t0, double t1) const;
};

}  // namespace kiri::geometry::detail
