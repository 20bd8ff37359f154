#pragma once
// Internal: the base surfaces as linear maps of the control-mesh vertices. Both surface kinds
// (Catmull-Clark limit, Gregory network) are linear in the control points, so a point of face
// f at (u, v) is sum_k w_k(u, v) P[support_k]; the fit and the tessellator need only these
// weights (DESIGN "connectivity apart from coordinates": built once per topology).
#include <memory>
#include <vector>

#include "kiri/geometry/terrain/mesh.hpp"

namespace kiri::geometry {

//! Weights of one face at (u, v), face parameterised with corner k of its vertex list (in
//! OpenMesh fv order) at (0,0), (1,0), (1,1), (0,1).
struct FaceWeights {
    std::vector<double> w, wu, wv, wuu, wuv, wvv;  // support-sized
};

class FaceStencils {
public:
    virtual ~FaceStencils() = default;
    int num_faces() const { return static_cast<int>(support_.size()); }
    const std::vector<int>& support(int face) const { return support_[face]; }
    //! True when the face reproduces affine functions of (u, v) from control points on a
    //! square grid (regular Catmull-Clark patch; Gregory face without irregular interior corner).
    virtual bool regular(int face) const = 0;
    //! Fills out (sized to the support) up to derivatives of the given order (0, 1 or 2).
    virtual void weights(int face, double u, double v, FaceWeights& out, int order = 1) const = 0;

protected:
    std::vector<std::vector<int>> support_;
};

//! Catmull-Clark limit surface through OpenSubdiv Bfr (boundary: edges and corners
//! interpolated, VTX_BOUNDARY_EDGE_AND_CORNER; [OpenSubdiv]).
std::unique_ptr<FaceStencils> make_catmull_clark_stencils(const PolyMesh& mesh);

//! Gregory patch network ([Loop09]; patches as [Thesis] (2.1)-(2.5)) over a quad
//! mesh, as 20 control points per face that are fixed combinations of the mesh vertices.
std::unique_ptr<FaceStencils> make_gregory_stencils(const PolyMesh& mesh);

}  // namespace kiri::geometry
