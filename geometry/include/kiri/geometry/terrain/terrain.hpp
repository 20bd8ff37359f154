#pragma once
//! \file terrain.hpp
//! Terrain: heightfield + triangle mesh + spatial queries (height, normal, ray, closest point).
#include <memory>
#include <optional>

#include <glm/vec3.hpp>

#include "kiri/geometry/terrain/heightfield.hpp"
#include "kiri/geometry/terrain/mesh.hpp"

namespace kiri::geometry {

struct RayHit {
    double t = 0.0;  //!< distance along the (normalised) direction
    glm::dvec3 point{0.0};
    glm::dvec3 normal{0.0, 0.0, 1.0};  //!< unit normal of the hit triangle, z >= 0
};

struct Bounds3 {
    glm::dvec3 min{0.0}, max{0.0};
};

//! A terrain in local metres. Each grid cell is split into two triangles along the diagonal
//! from sample (i, j) to (i + 1, j + 1); height() and normal() interpolate exactly on those
//! triangles, so they agree with mesh(), ray and closest-point queries.
//! The mesh and the AABB tree (CGAL, inside the .cpp) are built on first use: a scene that
//! only renders never pays for them. Threads: the first call that creates the index must not
//! race with another one (run one query, or mesh(), before sharing a Terrain between
//! threads); after that the const queries are safe to call concurrently.
class Terrain {
public:
    explicit Terrain(Heightfield heightfield);
    ~Terrain();
    Terrain(Terrain&&) noexcept;
    Terrain& operator=(Terrain&&) noexcept;

    const Heightfield& heightfield() const { return hf_; }
    Bounds3 bounds() const;

    //! Height at (x, y); points outside the grid take the nearest edge's value.
    double height(double x, double y) const;
    //! Unit upward normal at (x, y) of the triangle containing it.
    glm::dvec3 normal(double x, double y) const;
    //! First hit of the ray origin + t dir (t >= 0) with the mesh, if any.
    std::optional<RayHit> intersect_ray(const glm::dvec3& origin, const glm::dvec3& dir) const;
    //! Closest point of the mesh to p.
    glm::dvec3 closest_point(const glm::dvec3& p) const;

    //! Triangle mesh of the grid (double precision OpenMesh), built on first call.
    const TriMesh& mesh() const;

private:
    Heightfield hf_;
    struct Index;  // mesh + CGAL AABB tree, built lazily
    mutable std::unique_ptr<Index> index_;
    const Index& index() const;
};

}  // namespace kiri::geometry
