#pragma once
//! \file attenuation_cpu.hpp
//! The 3D attenuation buffer ([Shimada08] (7), sections 3.2-3.3) computed on the CPU, with exactly
//! the GPU's discretisation (render/src/attenuation_buffer.cpp): the oracle of the GL pass and the
//! subject of the unit tests that compare the buffer with the exact Harris pass.
//!
//! Each voxel holds log Gamma = sum of log G_i over the particles whose shadow cylinder holds the
//! voxel's centre. The cylinder of particle i is its disc perpendicular to the light swept away
//! from the sun: in column (c_u, c_v) at distance rho from the particle's axis (rho < r, the true
//! chord of the disc in each row of columns) it holds log G_i(rho) from the slice
//! shadow_start(w_i) on. It is written as its first voxel (the deposit) and extended along the
//! column by a prefix sum, which writes every voxel of the cylinder in O(footprint) instead of
//! O(footprint x length). Sums are order independent: no sorting.
//!
//! Reading: trilinear interpolation of log Gamma (GL_LINEAR, clamp to edge), minus what the buffer
//! holds of the particle being lit itself (Harris's particle is not lit through itself), then exp.
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "kiri/geometry/particles/light_grid.hpp"
#include "kiri/geometry/particles/particles.hpp"

namespace kiri::geometry {

//! log Gamma never goes below this (the GPU's exp() of float underflows soon after).
constexpr double min_log_gamma = -80.0;

struct AttenuationVolume {
    LightGrid grid;
    std::vector<float> log_gamma;  //!< voxel (i, j, k) at (k size[1] + j) size[0] + i
};

//! Builds the buffer in double, stored as float.
AttenuationVolume build_attenuation_cpu(const ParticleCloud& cloud, const LightGrid& grid);

//! log G of particle p's footprint in the light column (du, dv) metres across the light from its
//! axis: the ball's column there between the planes of the fog's floor and top
//! (footprint_ray_share along the light), its optical depth times mass_gain(p.above_ground), so
//! the mass the ground and the planes cut off shades the fog as the rest (the billboard draws it
//! so too). A lake's skin lay in the shadow columns of the balls under it, whose upper parts
//! stood out of the lake: read a third of an optical depth deep where the Medium has none; and
//! the quarter of the lake's mass in the ground shaded nothing above it (docs/particles.md).
double column_log_gain(const LightGrid& grid, const Particle& p, double forward, double du, double dv);

//! The voxels of particle p's footprint: calls fn(i, j, k, log_g) for every column (i, j) within
//! its radius whose shadow starts inside the grid (k = max(shadow_start, 0)), log_g its
//! column_log_gain.
template <typename Fn>
void for_each_deposit(const LightGrid& grid, const Particle& p, double forward, Fn&& fn);

//! log Gamma at world point p, trilinear with clamp to edge, as the GPU's sampler reads it.
double sample_log_gamma(const AttenuationVolume& volume, const glm::dvec3& p);
//! What the buffer's trilinear read at world point q holds of particle `self`'s own cylinder.
double self_log_gamma(const LightGrid& grid, const Particle& self, double forward, const glm::dvec3& q);
//! What the read at q would hold of particle `self`'s footprint if its shadow started before q:
//! the footprint's log gain in the read's four columns, weighted as the read weighs them.
double own_column_log_gain(const LightGrid& grid, const Particle& self, double forward, const glm::dvec3& q);
//! Gamma of particle k at its centre: exp(sample - self), in (0, 1] (Harris: a particle is not
//! lit through itself).
double particle_gamma(const AttenuationVolume& volume, const ParticleCloud& cloud, std::size_t k);
//! The share of its own footprint's column that shades a particle's billboard. A particle stands
//! for the Medium around it, and the blue-noise sampler keeps the others away from it: its
//! neighbourhood holds about one particle less than the Medium would (a hyperuniform set), half of
//! it towards the sun. The particle's own mass, spread as its footprint, makes that up.
inline constexpr double billboard_own_share = 0.5;
//! A share (billboard_own_share, or the particle's calibrated_own_share) at point q of particle
//! `self`'s billboard, the sun towards `light` (unit): the part missing towards the sun lies
//! within about a radius of the particle, so where the ray towards the sun leaves the fog by its
//! top sooner (`Particle::top`'s plane), less of it: the share times that distance over the
//! radius, at most 1. Near a fog lake's top the whole share lit the skin as if under a third of
//! an optical depth of fog, where the Medium has almost none.
double billboard_own_share_at(const Particle& self, const glm::dvec3& light, const glm::dvec3& q,
                              double share = billboard_own_share);
//! log Gamma at point q of particle `self`'s billboard, as particles.frag reads it: the read less
//! its own cylinder, plus billboard_own_share_at (of `share`) of its footprint's column, in
//! [min_log_gamma, 0] (docs/particles.md, "Lit as the Medium").
double billboard_log_gamma(const AttenuationVolume& volume, const Particle& self, double forward, const glm::dvec3& q,
                           double share = billboard_own_share);
//! The bounds of a particle's calibrated share of its own column: below 0 it takes part of its
//! column out where the footprints of the particles up-sun already read more than the Medium.
inline constexpr double min_own_share = -1.0, max_own_share = 4.0;
//! The share of its own column that makes particle `self`'s billboard read the Medium's optical
//! depth towards the sun, `tau_sun`, at its centre: half its column made the missing
//! neighbourhood up in a deep slab, two or three times that in fog a particle or two deep (a
//! valley lake) and under the froxels' share of the fog in combined mode. In [min_own_share,
//! max_own_share];
//! billboard_own_share where its own column is too thin to measure by (particle_light.comp).
double calibrated_own_share(const AttenuationVolume& volume, const Particle& self, double forward, double tau_sun);

}  // namespace kiri::geometry

#include "kiri/geometry/particles/attenuation_cpu_impl.hpp"
