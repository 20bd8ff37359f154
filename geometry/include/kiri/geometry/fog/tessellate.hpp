#pragma once
//! \file tessellate.hpp
//! Triangles from the base surface: uniform N x N per patch, or adaptive to a
//! tolerance, crack-free between patches of different levels.
#include <vector>

#include "kiri/geometry/fog/base_surface.hpp"
#include "kiri/geometry/terrain/mesh.hpp"

namespace kiri::geometry {

struct TessellationOptions {
    int level = 8;           //!< (the source used 4..10)
    double tolerance = 0.0;  //!< 0: uniform
    int max_level = 64;
    bool operator==(const TessellationOptions&) const = default;
};

//! The "tessellation" object of the scene's "fog" section.
template <fields_of<TessellationOptions> O, class V>
void visit_fields(O& o, V&& v)
{
    v(o.level,
      {.key = "level", .range = closed(1, 256), .doc = "uniform: N x N cells per patch", .widget = closed(1, 64)});
    v(o.tolerance,
      {.key = "tolerance",
       .unit = "m",
       .range = greater_than(0),
       .doc = "adaptive instead: the maximum distance to the exact surface",
       .widget = closed(0.05, 100),
       .log_widget = true,
       .shown_default = "none (uniform)",
       .omit_default = true});
    v(o.max_level, {.key = "max_level", .range = closed(1, 256), .doc = "adaptive: the finest level a patch may get"});
}

//! The triangles and, per vertex: position, unit normal, (u, v) of its patch in the texture
//! coordinates (mesh.texcoord2D), and the patch id in the OpenMesh property named
//! `patch_id_property` (int). Each patch has its own vertices (full per-patch UVs, [Thesis]
//! 2.2.2); vertices on a shared edge or corner are evaluated once, by the patch of smallest id,
//! and copied, so neighbours' edge vertices coincide exactly. Each edge gets one level (the
//! larger of its two patches'); a patch meets edges finer than itself with transition
//! triangles (a strip between its inner ring and the edge).
struct Tessellation {
    TriMesh mesh;
    std::vector<int> patch_level;  //!< interior level of each patch
    double max_error = 0.0;        //!< measured max |S(u,v) - triangle| (m), see tessellation_error
};

inline constexpr const char* patch_id_property = "patch_id";

//! \throw InputError on a level < 1 or a non-finite / negative tolerance.
Tessellation tessellate(const BaseSurface& surface, const TessellationOptions& options);

//! Max over triangles of |S(u, v) - linear interpolation| at 10 barycentric points per
//! triangle (corners excluded): the distance from each triangle point to the surface point of
//! the same (u, v), an upper bound of the distance to the exact surface.
double tessellation_error(const BaseSurface& surface, const TriMesh& mesh);

}  // namespace kiri::geometry
