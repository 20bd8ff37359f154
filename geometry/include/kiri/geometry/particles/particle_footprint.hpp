#pragma once
//! \file particle_footprint.hpp
//! What one particle does to the light that passes it ([Shimada08] (7)), written once
//! here for the exact reference, the CPU attenuation buffer and the tests; the GPU's copy is
//! render/shaders/particle_footprint.glsl (checked against this file by a GL test).
//!
//! Footprint: a ray passing at distance rho from the centre of particle k (radius r) crosses the
//! optical depth tau_k f(rho / r) with the Gaussian
//!
//!   f(x) = (exp(-x^2 / (2 s^2)) - e0) / (1 - e0),  s = 0.4,  e0 = exp(-1 / (2 s^2)),  x < 1;  f = 0 beyond,
//!
//! shifted so it reaches 0 at the rim (no step where the billboard ends).
//! Transmittance T = exp(-tau f). Light gain G = T + a c (1 - T) with c = p(l,l)/4pi: the part of
//! the removed light that the particle scatters forward stays in the beam. Shimada (7) writes
//! G = a tau c + T, the optically thin limit of this (a tau ~ a (1 - T)); the saturating form keeps
//! G <= 1 for every tau (a particle never adds light) and gives an opaque particle G = a c.
//! log G is clamped at min_log_gain, so an opaque black particle gives a finite value, never -inf.
#include <cmath>
#include <functional>
#include <utility>

#include <glm/vec3.hpp>

namespace kiri::geometry {

//! A particle passes at least e^-16 (1.1e-7) of the light: opaque for every purpose.
constexpr double min_log_gain = -16.0;
//! The Gaussian's standard deviation in units of the radius.
constexpr double footprint_sigma = 0.4;

//! f(x) above, x = rho / r >= 0; 1 at the centre, 0 for x >= 1.
double footprint_profile(double x);
//! Integral of f(rho / r) over the plane, in units of r^2 (0.861): tau_k r^2 times it is the
//! particle's extinction cross-section integral (m^2).
double footprint_area();
//! log G at distance rho from the axis of a particle (radius r, optical depth tau, albedo a) with
//! forward-scattering fraction c; 0 for rho >= r; in [min_log_gain, 0]; tau may be +inf.
double footprint_log_gain(double rho, double radius, double optical_depth, double albedo, double forward);
//! Transmittance exp(-tau f(rho / r)) of the billboard (what it hides of what lies behind it).
double footprint_transmittance(double rho, double radius, double optical_depth);

// The particle in three dimensions: the density k(q) = exp(-q^2 / (2 (s r)^2)) - e0 at distance
// q < r from the centre, 0 beyond (the footprint's Gaussian, reaching 0 at the rim). A ray from
// inside the particle, or one ending at the terrain within it, crosses only part of its column.

//! Of the column a ray passing rho = x r from the centre crosses (tau f(x)), the share between
//! u0 and u1: metres along the ray from its point nearest the centre. 1 for the whole chord,
//! 0 for x >= 1 or u1 <= u0. (GLSL twin: particle_footprint.glsl.)
double footprint_ray_share(double x, double radius, double u0, double u1);
//! The share of the particle's mass that lies above the ground z = ground(x, y): 1 for a
//! particle wholly above it, 1/2 for one centred on a plane, 0 for one buried. Each vertical
//! column through the ball is split in closed form at the ground's height there; the columns
//! are summed over the disc by a polar quadrature of 96 points (the ground's relief within the
//! disc counts, not only the height under the centre). NaN heights count as no ground.
double footprint_share_above(const glm::dvec3& centre, double radius,
                             const std::function<double(double, double)>& ground);
//! The share of the particle's mass between z = slab(x, y).first and .second (below and above,
//! each column split in closed form at both, by the same quadrature): footprint_share_above with
//! a ceiling too. NaN bounds count as none; a column whose ceiling is under its floor holds none.
double footprint_share_between(const glm::dvec3& centre, double radius,
                               const std::function<std::pair<double, double>(double, double)>& slab);

//! The particle's density (1/m) at distance q from its centre: tau k(q / r) / (r K0), K0 the
//! column of k through the centre in units of the radius (0.902), so that column holds tau.
//! 0 for q >= r. (particles.frag integrates it along a chord with particle_footprint.glsl's
//! chord_integral_at.)
double ball_density(double q, double radius, double optical_depth);
//! The integral of that density over the ball, in units of tau r^2 (0.801; a billboard's footprint
//! holds footprint_area, 0.861).
double ball_mass();
//! The integral of that density along a ray passing rho = x r from the centre, from u0 to u1
//! (metres along the ray from its point nearest the centre), over tau: in [0, 1], 1 for the whole
//! chord through the centre. Its ratio to the whole chord's is footprint_ray_share.
double ball_chord_share(double x, double radius, double u0, double u1);

//! The least share of a particle's mass that is drawn as the whole of it: below it the visible
//! remnant of a particle cut by the ground or a plane would turn into a dense speck.
constexpr double min_share_drawn = 0.25;
//! What a particle's optical depth is multiplied by where only `share` of its mass is drawn, so
//! that the part cut off adds to the rest: 1 / share, clamped to [min_share_drawn, 1] (NaN: 1).
double mass_gain(double share);

}  // namespace kiri::geometry
