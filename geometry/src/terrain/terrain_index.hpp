#pragma once
// Internal: the terrain's triangle mesh and its CGAL AABB tree, behind a plain interface so
// that CGAL stays inside terrain_index.cpp (its headers cost ~30 s and ~1.7 GB per file).
#include <memory>
#include <optional>

#include "kiri/geometry/terrain/terrain.hpp"

namespace kiri::geometry {

struct Terrain::Index {
    explicit Index(const Heightfield& hf);
    ~Index();
    const TriMesh& mesh() const;
    std::optional<RayHit> intersect_ray(const glm::dvec3& origin, const glm::dvec3& dir) const;
    glm::dvec3 closest_point(const glm::dvec3& p) const;

    struct Impl;
    std::unique_ptr<Impl> impl;
};

}  // namespace kiri::geometry
