#pragma once
//! \file light_grid.hpp
//! The voxel grid of the 3D attenuation buffer ([Shimada08] 3.3, the "3D intensity space"):
//! columns along the light, enclosing every particle. Shared by the GPU buffer (render) and its
//! CPU twin (attenuation_cpu.hpp) so both discretise the same way.
//!
//! Light frame: L towards the sun (unit), U and V orthonormal and perpendicular to it. A point p
//! has u = U.p, v = V.p and depth w = -L.p (growing away from the sun). The grid's third
//! coordinate is the sheared depth w' = w - a u - b v: a = b = 0 gives slices perpendicular to the
//! light (Shimada's layout); a plane fitted to the particles tilts the slices to follow flat fog.
//! A column (u, v fixed) is one ray of light in every case, so the order along it is the order
//! towards the sun that Harris sorts by.
//!
//! Voxel (i, j, k) covers [i, i+1) x [j, j+1) x [k, k+1) in grid coordinates
//! g = ((u - u0) / du, (v - v0) / dv, (w' - w0) / dw); its centre is at + 0.5. The first and last
//! columns and the first slice are left empty, so a lookup outside the particles reads Gamma = 1.
#include <array>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "kiri/geometry/particles/particles.hpp"

namespace kiri::geometry {

struct LightGrid {
    glm::dvec3 light{0.0, 0.0, 1.0};  //!< L, towards the sun, unit
    glm::dvec3 u_axis{1.0, 0.0, 0.0}, v_axis{0.0, 1.0, 0.0};
    double shear_u = 0.0, shear_v = 0.0;   //!< a, b of w' = w - a u - b v
    glm::dvec3 origin{0.0};                //!< (u0, v0, w0)
    glm::dvec3 voxel{1.0};                 //!< (du, dv, dw), metres
    std::array<int, 3> size{1, 1, 1};      //!< voxels along u, v, w'
    LightFrame frame = LightFrame::light;  //!< what was chosen (never automatic)

    std::size_t voxel_count() const { return std::size_t(size[0]) * size[1] * size[2]; }
    //! (u, v, w) of a world point.
    glm::dvec3 light_coordinates(const glm::dvec3& p) const;
    //! Continuous grid coordinates g of a world point (see the file comment).
    glm::dvec3 to_grid(const glm::dvec3& p) const;
    //! The affine map world -> texture coordinates g / size (GL's [0, 1]^3), column-major.
    glm::dmat4 world_to_texture() const;
    //! Centre (u, v) of column (i, j).
    double column_u(int i) const { return origin.x + (i + 0.5) * voxel.x; }
    double column_v(int j) const { return origin.y + (j + 0.5) * voxel.y; }
    //! The slice where the shadow of a particle at light depth w starts in column (i, j): the
    //! first voxel whose centre lies at or beyond w along the column (may be < 0 or >= size[2];
    //! callers clamp below at 0 and skip beyond the end).
    int shadow_start(double w, int i, int j) const;
};

struct LightGridOptions {
    int resolution = 128;  //!< voxels along each axis
    LightFrame frame = LightFrame::automatic;
    int depth_resolution = 0;  //!< slices along the light when > 0 (else `resolution`)
};

//! The grid for a cloud and a light direction (towards the sun; normalised here). Encloses every
//! particle's sphere and shadow start with one empty voxel around. `automatic` picks the sheared
//! frame when its slices span less depth than the unsheared one. \throw std::invalid_argument for
//! a zero or non-finite light, an empty cloud or a resolution outside [4, 1024].
LightGrid make_light_grid(const ParticleCloud& cloud, const glm::dvec3& light, const LightGridOptions& options = {});

}  // namespace kiri::geometry
