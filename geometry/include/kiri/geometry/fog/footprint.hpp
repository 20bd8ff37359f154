#pragma once
//! \file footprint.hpp
//! Where the fog lies seen from above (a polygon in local metres) and the quad control mesh
//! built over it (DESIGN "FogRegion -> ControlMesh").
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "kiri/geometry/terrain/mesh.hpp"
#include "kiri/geometry/terrain/terrain.hpp"

namespace kiri::geometry {

//! A simple polygon in local metres (x east, y north); either orientation, not closed
//! (the last vertex joins the first). Fog in several places at once (a fill from several seeds
//! or basins, fog_placement.hpp) adds further polygons in `more`.
struct Footprint {
    std::vector<glm::dvec2> polygon;
    //! Further simple polygons; no two polygons touch or lie inside one another. The control
    //! mesh covers their union.
    std::vector<std::vector<glm::dvec2>> more;
    bool operator==(const Footprint&) const = default;
};

//! polygon followed by more (the non-empty ones).
std::vector<std::vector<glm::dvec2>> footprint_polygons(const Footprint& footprint);

//! The axis-aligned rectangle [min, max] as a footprint.
Footprint rectangle_footprint(glm::dvec2 min, glm::dvec2 max);

//! Checks a footprint: at least 3 finite vertices, no repeated consecutive vertex, positive
//! area and no two edges crossing or touching except neighbours at their shared vertex; with
//! several polygons, also that no two of them touch or nest.
//! \throw InputError(label, "footprint", reason) naming the offending vertex or edges (and
//!        the polygon, counting `polygon` as 0, when there are several).
void validate_footprint(const Footprint& footprint, const std::string& label = {});

//! Quad control mesh over a footprint. Connectivity comes from a square grid of cell size
//! patch_size aligned on the footprint's bounding box: a cell is kept when its centre lies
//! inside the polygon (always at least one cell, so a footprint smaller than a patch gets
//! one patch); diagonal-only contacts are closed by adding a cell (keeps the mesh manifold).
//! Boundary vertices are then moved onto the polygon (its corners first, then the closest
//! border point), backing off where a quad would fold, so the mesh conforms to the border.
struct ControlMesh {
    PolyMesh mesh;                 //!< quads, counter-clockwise seen from above (+z)
    std::vector<glm::ivec2> grid;  //!< grid index (i, j) of each vertex (topology only)
    double patch_size = 0.0;       //!< metres
    glm::dvec2 origin{0.0};        //!< local frame of the fit: footprint bounding-box centre
    glm::dvec2 grid_origin{0.0};   //!< position of grid index (0, 0) before snapping
    int boundary_vertices = 0;
    int snapped_vertices = 0;  //!< boundary vertices lying on the polygon after snapping

    int num_faces() const { return static_cast<int>(mesh.n_faces()); }
    int num_vertices() const { return static_cast<int>(mesh.n_vertices()); }
};

struct ControlMeshOptions {
    double patch_size = 500.0;      //!< metres, > 0
    bool conform_to_border = true;  //!< snap boundary vertices onto the polygon
    int max_faces = 1 << 20;        //!< LimitError above this, before allocating
    bool operator==(const ControlMeshOptions&) const = default;
};

//! Builds the control mesh; vertex heights are the terrain's height under each vertex.
//! \throw InputError (invalid footprint, footprint not inside the terrain's extent: kiri does
//!        not clip, it names the first vertex outside), LimitError (too many faces).
ControlMesh build_control_mesh(const Footprint& footprint, const Terrain& terrain, const ControlMeshOptions& options,
                               const std::string& label = {});

}  // namespace kiri::geometry
