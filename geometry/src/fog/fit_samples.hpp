#pragma once
// Internal: where the fit looks at the terrain. Every terrain grid vertex under the control
// mesh is a sample (the piecewise-linear terrain peaks at its vertices, so holding the
// clearance there holds it wherever the surface is concave, i.e. over every ridge), plus a
// few (u, v) samples per patch so that every patch has data on coarse terrains.
#include <vector>

#include <glm/vec2.hpp>

#include "kiri/geometry/fog/footprint.hpp"
#include "kiri/geometry/terrain/heightfield.hpp"
#include "surface/face_stencil.hpp"

namespace kiri::geometry {

struct FitSamples {
    std::vector<std::size_t> face_begin;  // samples of face f: [face_begin[f], face_begin[f+1])
    std::vector<glm::dvec2> uv;
    long long grid_vertex_samples = 0;
    long long unresolved = 0;  // grid vertices near the border whose (u, v) Newton missed
};

//! (u, v) of every terrain grid vertex inside the control mesh (closed form on affine faces,
//! Newton elsewhere) and per_side x per_side cell-centred (u, v) samples per face.
FitSamples make_fit_samples(const ControlMesh& control, const FaceStencils& stencils, const Heightfield& hf,
                            int per_side, bool grid_vertices);

}  // namespace kiri::geometry
