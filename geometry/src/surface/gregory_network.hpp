#pragma once
// Internal: the G1 Gregory patch network of a quad mesh ([Loop09], "LSNC") as a linear map
// from the mesh vertices to the 20 points of each patch. Built once per topology; positions
// enter only through apply() (connectivity apart from coordinates).
#include <vector>

#include <glm/vec3.hpp>

#include "kiri/geometry/surface/gregory_patch.hpp"
#include "kiri/geometry/terrain/mesh.hpp"

namespace kiri::geometry {

struct GregoryNetworkMap {
    //! Per face: the mesh vertices its 20 points depend on (sorted).
    std::vector<std::vector<int>> support;
    //! Per face: 20 x support.size() row-major; point k (storage order of GregoryPatch) is
    //! sum_s matrix[k * n + s] * X[support[s]]. Each row sums to 1 (affine combinations).
    std::vector<std::vector<double>> matrix;

    int num_faces() const { return int(support.size()); }
    //! The patch of `face` for vertex positions X (indexed by vertex id).
    GregoryPatch patch(int face, const std::vector<glm::dvec3>& X) const;
};

//! Patch of face f: corner k of its vertex list (OpenMesh fv order) at (0,0), (1,0), (1,1),
//! (0,1) of the patch. Rules (LSNC for the interior; ours on the boundary, documented in
//! kiri/geometry/surface/surface.hpp). \throw InputError on a face that is not a quad, an isolated or
//! non-manifold vertex.
GregoryNetworkMap build_gregory_network(const PolyMesh& mesh);

}  // namespace kiri::geometry
