#pragma once
// Internal: the OpenSubdiv topology of a control mesh ([OpenSubdiv]). OpenSubdiv headers stay
// in geometry/src.
#include <memory>

#include <opensubdiv/far/topologyRefiner.h>

#include "kiri/geometry/terrain/mesh.hpp"

namespace kiri::geometry {

//! Catmull-Clark refiner over the faces of `mesh` (vertex ids = OpenMesh ids, face corners
//! in fv order), boundary VTX_BOUNDARY_EDGE_AND_CORNER (the default NONE drops the border
//! faces of an open mesh). \throw InputError if OpenSubdiv refuses the topology.
std::unique_ptr<OpenSubdiv::Far::TopologyRefiner> make_catmark_refiner(const PolyMesh& mesh);

}  // namespace kiri::geometry
