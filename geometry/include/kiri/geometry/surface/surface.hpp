#pragma once
//! \file surface.hpp
//! One interface over the two smooth surfaces of a quad control mesh:
//!
//! - `SurfaceKind::gregory`: one bicubic Gregory patch per face (gregory_patch.hpp), joined
//!   with G1 continuity by [Loop09] ("LSNC"). Interior vertices
//!   of any valence use LSNC: corner = Catmull-Clark limit position, edge points
//!   p + (2/3) lambda q_i on the limit tangent plane, face points from the G1 condition
//!   f = (1/3)[c_far p + (3 - 2 c_near - c_far) e + 2 c_near e' + r], c = cos(2 pi / n).
//!   Boundary rules (open meshes, e.g. a fog footprint):
//!   * boundary curves are the Catmull-Clark boundary limit, the cubic B-spline of the
//!     boundary vertices: p = (w_a + 4 v + w_b) / 6, edge points (2 v + w) / 3; they are
//!     shared exactly with the OpenSubdiv surface;
//!   * a vertex with one face (valence 2) is a corner: p = v, the tensor B-spline rules
//!     (OpenSubdiv's EDGE_AND_CORNER corner), c = 0;
//!   * a vertex with k >= 2 faces (valence k + 1) is smooth: its edge points lie on the half
//!     disc p + cos(j pi / k) A + sin(j pi / k) B (j = 0..k from one boundary edge to the
//!     other), A = (w_0 - w_k) / 6 along the boundary, B = (2/9)[2 (F - v) + (E - v)
//!     - (m_0 - v) - (m_k - v)] across it (F, E: sin-weighted means of the face centroids and
//!     interior edge midpoints, m_0, m_k the boundary edge midpoints), so all share one tangent
//!     plane and c = cos(pi / k) enters the G1 face points; for k = 2 (valence 3) this is the
//!     bicubic B-spline exactly;
//!   * on a boundary edge the face missing across it is replaced by the reflection of the
//!     inner one (m_out = 2 v - m_in, c_out = 2 m_edge - c_in).
//!   On a regular grid (interior valence 4, boundary valence 3 and corners of valence 2) the
//!   network is the bicubic B-spline surface, equal to OpenSubdiv's limit.
//! - `SurfaceKind::catmull_clark`: the Catmull-Clark limit surface (OpenSubdiv Bfr over a
//!   Far::TopologyRefiner, VTX_BOUNDARY_EDGE_AND_CORNER so that border faces are kept).
//!
//! Both surfaces are linear in the control points: a point of face f at (u, v) is
//! sum_s w_s(u, v) X[support_s]. The topology and these stencils are built once; new control
//! positions (a refit) go through set_control_points() without rebuilding anything.
#include <memory>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "kiri/geometry/surface/gregory_patch.hpp"
#include "kiri/geometry/terrain/mesh.hpp"

namespace kiri::geometry {

enum class SurfaceKind {
    gregory,        //!< G1 network of bicubic Gregory patches
    catmull_clark,  //!< Catmull-Clark limit surface (OpenSubdiv)
};

//! Parameter domain of a face: [u0, u1] x [v0, v1] (the unit square for every quad face).
struct FaceDomain {
    double u0 = 0.0, v0 = 0.0, u1 = 1.0, v1 = 1.0;
};

class Surface {
public:
    virtual ~Surface() = default;
    virtual SurfaceKind kind() const = 0;
    int num_faces() const { return int(support_.size()); }
    int num_control_points() const { return int(points_.size()); }
    //! Corner k of the face's vertex list (OpenMesh fv order) sits at (0,0), (1,0), (1,1), (0,1).
    FaceDomain domain(int /*face*/) const { return {}; }

    //! Position, first derivatives and unit normal (never NaN; same fallbacks as unit_normal
    //! of gregory_patch.hpp). (u, v) are clamped to the domain. \throw InputError on a bad face.
    virtual PatchPoint evaluate(int face, double u, double v) const = 0;
    //! Batch of one face: positions and first derivatives (normals if out.nx is not empty).
    //! Allocates nothing. \throw InputError on a bad face or short spans.
    virtual void evaluate_into(int face, std::span<const double> u, std::span<const double> v,
                               const PatchSampleSpans& out) const = 0;
    //! Convenient form of evaluate_into.
    PatchSamples evaluate(int face, std::span<const double> u, std::span<const double> v, bool normals = true) const;

    //! Control vertices (mesh vertex ids) that face `face` depends on.
    std::span<const int> support(int face) const { return support_.at(face); }
    //! Weights of the support at (u, v): S = sum w[s] X[support[s]], dS/du = sum wu[s] ...
    //! Spans must hold support(face).size() values. Allocates nothing.
    virtual void weights(int face, double u, double v, std::span<double> w, std::span<double> wu,
                         std::span<double> wv) const = 0;

    //! Control positions, indexed by mesh vertex id.
    const std::vector<glm::dvec3>& control_points() const { return points_; }
    //! New positions for the same topology (e.g. after a fit); stencils are kept.
    //! \throw InputError on a wrong count or a non-finite coordinate.
    void set_control_points(std::span<const glm::dvec3> points);

    //! The Gregory patch of a face (gregory kind only; nullptr otherwise).
    virtual const GregoryPatch* gregory_patch(int /*face*/) const { return nullptr; }

protected:
    virtual void control_points_changed() {}
    void check_face(int face) const;
    std::vector<std::vector<int>> support_;
    std::vector<glm::dvec3> points_;
};

//! Builds the surface of a quad mesh (positions taken from the mesh).
//! \throw InputError on a non-quad face (gregory), an isolated or non-manifold vertex, or a
//!        topology OpenSubdiv refuses.
std::unique_ptr<Surface> make_surface(const PolyMesh& mesh, SurfaceKind kind);

const char* to_string(SurfaceKind kind);

}  // namespace kiri::geometry
