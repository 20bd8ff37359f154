#pragma once
//! \file light_volume.hpp
//! The light scattered at least once inside the fog, precomputed: a light-transport volume in
//! the Medium's shell coordinates, baked by tracing the sun's light forward through the fog
//! (kiri/geometry/reference/light_volume_bake.hpp) and read by the lighting model's `baked`
//! multiple scattering (fog_lighting.hpp, docs/medium.md "Multiple scattering from a baked
//! light-transport volume").
//!
//! It stores, per cell, the real spherical-harmonic moments L_lm = integral L_d(w) Y_lm(w) dw of
//! the diffuse radiance L_d (the light travelling in direction w that has scattered at least
//! once) for a sun of unit radiance (irradiance pi). Henyey-Greenstein's Legendre coefficients are
//! g^l ([HG41]), so by the Funk-Hecke theorem ([Ramamoorthi01]) the light it scatters towards o is
//!
//!   integral p_HG(w . o, g) L_d(w) dw = sum_l g^l sum_m L_lm Y_lm(o)
//!
//! (the convolution is exact; the truncation at `bands` bands is the approximation). The cells
//! follow the shell: (x, y) on a regular grid, h = (z - floor) / (top - floor) in `levels`
//! equal levels, so a thin layer and a deep lake get the same number of levels (the top raised to
//! the height fog's where that is higher, the floor lowered to the ground where the height fog
//! lies under the Medium's: shell()).
//!
//! A cell can hold two bodies of fog that see very different diffuse light: a thick valley lake
//! and a thin thread of fog across a ridge. The light a column of fog scatters grows with its
//! optical thickness, tau_c = column_extinction coverage (top - floor), and saturates where it is
//! thick, so with column_extinction > 0 the cells store their diffuse light divided by their mean of
//! column_scale = 1 - exp(-tau_c) (volume-weighted over the cell's footprint), and the lookup
//! multiplies the interpolated moments back by column_scale at its own (x, y): the thread gets the
//! lake's light scaled by its own thinness, and a fog of even thickness (a slab, a blanket) is as
//! before. A renderer mirroring the lookup computes column_scale from the shell's floor, top and
//! coverage at the point (one exp) and passes it to moments_at / in_scattered.
#include <vector>

#include <glm/vec3.hpp>

#include "kiri/geometry/medium/medium.hpp"

namespace kiri::geometry {

//! At most this many spherical-harmonic bands (l < 8).
inline constexpr int light_volume_max_bands = 8;

//! Real orthonormal spherical harmonics Y_lm(d) of the unit direction d for l < bands (clamped
//! to [1, light_volume_max_bands]), at out[l (l + 1) + m], m in [-l, l]; out holds bands^2 values.
void real_spherical_harmonics(const glm::dvec3& d, int bands, double* out);

//! h of the light volume at height z of a column: (z - floor) / (top - floor), or -1 where the
//! column holds no shell (top <= floor) or z is outside [floor, top].
double shell_height(const MediumColumn& column, double z);

struct LightVolume {
    //! Cell (i, j, k) spans [x0 + i dx, x0 + (i + 1) dx] x [y0 + j dy, ...] x h in [k, k + 1] / nz.
    int nx = 0, ny = 0, nz = 0;
    int bands = 0;  //!< spherical-harmonic bands stored (bands^2 moments per cell)
    double x0 = 0.0, y0 = 0.0, dx = 1.0, dy = 1.0;
    //! L_lm of each cell, index ((k ny + j) nx + i) bands^2 + l (l + 1) + m, for a sun of unit radiance.
    std::vector<double> moments;
    //! > 0: the moments are divided by the cell's mean column_scale (the file comment), to be
    //! multiplied by column_scale at the lookup point; 0: they are the diffuse light itself. The
    //! Medium's extinction times its mean profile (1 + top_density) / 2, 1/m.
    double column_extinction = 0.0;
    //! The height fog the sunlight also scatters in (volume/height_fog.hpp: haze_extinction up to
    //! haze_base, falling off over haze_scale_height above; extinction 0: none). Its light lies
    //! above the Medium's top too (a dense haze in the valleys over a thin blanket) and where the
    //! Medium has none, so the cells' columns reach up to haze_top wherever it is above their floor
    //! (shell), and its vertical optical depth counts in column_scale.
    double haze_extinction = 0.0, haze_base = 0.0, haze_scale_height = 1.0;
    double haze_top = 0.0;  //!< the height fog's top (HeightFog::top)
    //! Where the height fog lies under the Medium's floor (a blanket over a valley's haze), the
    //! cells' columns reach down to the ground: their floor on a grid of floor_nx x floor_ny
    //! samples spanning the cells' rectangle, bilinear between them, each the lower of the
    //! Medium's floor there and the lowest ground around it (the Medium's floor where the ground
    //! is above haze_top); empty: the Medium's floor.
    int floor_nx = 0, floor_ny = 0;
    std::vector<double> floors;
    //! The terrain's shadow. A cell can hold fog in the sun and fog deep in the terrain's shadow (a
    //! lake's arm behind a ridge), whose diffuse light differs a hundredfold: the shadowed fog
    //! sees only what reaches it from the sunlit fog, through air, around the ridge. Each cell
    //! keeps L_00 of its two parts apart (class_means, in the moments' units: two values a cell,
    //! index ((k ny + j) nx + i) 2 + {0 sunlit, 1 shadowed}; a part too small to measure takes its
    //! neighbours' mean, else the cell's), and the lookup at a point scales the moments by its
    //! part's L_00 over the cell's (in_scattered_at): the direction's shape from every photon, the
    //! magnitude from its own side of the shadow. The shadow's top: at each of shadow_nx x
    //! shadow_ny samples spanning the cells' rectangle (the floors' grid: two a DEM spacing, 4 to
    //! 16 a cell), the lowest height the sun reaches past the terrain upwind, bilinear between
    //! them (shadow_top_at): over a heightfield a column's shadowed part is one interval from the
    //! ground up. Empty: no terrain, one part.
    int shadow_nx = 0, shadow_ny = 0;
    std::vector<double> shadow_tops;
    std::vector<double> class_means;
    // What the bake cost.
    long long photons = 0;
    long long deposits = 0;
    double seconds = 0.0;

    bool empty() const
    {
        return nx < 1 || ny < 1 || nz < 1 || bands < 1 || bands > light_volume_max_bands || moments.empty();
    }
    //! The cells' floor at (x, y) from the floors' grid; +inf without one.
    double floor_at(double x, double y) const;
    //! The terrain's shadow's top at (x, y) from its grid; -inf without one.
    double shadow_top_at(double x, double y) const;
    //! Whether the volume keeps its cells' sunlit and shadowed parts apart (class_means).
    bool has_shadow_parts() const;
    //! The column of the cells at (x, y) from the Medium's there: its floor lowered to floor_at,
    //! its top raised to haze_top where the height fog reaches above it (and above the floor).
    MediumColumn shell(MediumColumn medium_column, double x, double y) const;
    //! 1 - exp(-tau_c) of the Medium's column at the lookup point, tau_c = column_extinction
    //! coverage (top - floor) plus the height fog's optical depth from the Medium's floor up to
    //! the shell's top (the height fog under the floor left out: counted, it took the default
    //! scene's view from above from 0.99 to 0.95 of the path tracer's brightness); at least 1e-6;
    //! 1 when column_extinction is 0.
    double column_scale(const MediumColumn& medium_column) const;
    //! The moments at (x, y, h), trilinear between cell centres (clamped to the outer cells' centres),
    //! times `scale` (column_scale of the point's column), into out (bands^2 values); zeros when empty.
    void moments_at(double x, double y, double h, double* out, double scale = 1.0) const;
    //! sum_l g^l sum_m L_lm Y_lm(towards) at (x, y, h): the diffuse light that the phase function
    //! of anisotropy g scatters towards the unit direction `towards`, per unit sun radiance
    //! (1/sr x sr = dimensionless radiance ratio); >= 0 and finite for any input, 0 when empty.
    //! `scale` as in moments_at.
    double in_scattered(double x, double y, double h, const glm::dvec3& towards, double g, double scale = 1.0) const;
    //! The same with the direction's part g^l Y_lm(towards) (phase_weights) computed once, as a
    //! ray marcher does along a ray.
    double in_scattered(double x, double y, double h, const double* weights, double scale = 1.0) const;
    //! in_scattered at the point (x, y, z) of shell height h, scaled by the L_00 of the cells' part
    //! on the point's side of the terrain's shadow over the cells' (class_means, both trilinear as
    //! the moments, the ratio clamped to [0, 64]); in_scattered where the volume has no parts.
    double in_scattered_at(double x, double y, double z, double h, const double* weights, double scale = 1.0) const;
    //! g^l Y_lm(towards) into out (bands^2 values).
    void phase_weights(const glm::dvec3& towards, double g, double* out) const;
};

}  // namespace kiri::geometry
