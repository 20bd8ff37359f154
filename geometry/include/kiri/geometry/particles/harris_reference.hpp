#pragma once
//! \file harris_reference.hpp
//! The exact light pass of [Harris01] as [Shimada08] (1)-(4) restates it, in
//! double: the ground truth the attenuation buffer is scored against.
//!
//! The particles are sorted towards the sun (by L.p, nearest the sun first; ties by index). The
//! light reaching particle k passes the particles j before it whose footprint covers k's centre,
//! at the distance rho_jk between k's centre and j's axis along the light, and follows the
//! recurrence (3)-(4) with p(l,l) constant:
//!
//!   I <- g_j + T_j I,   g_j = a_j c (1 - T_j) I,   T_j = exp(-tau_j f(rho_jk / r_j))
//!
//! starting at I = I0 = 1 (footprint and the saturating g: particle_footprint.hpp), each step at
//! least e^min_log_gain of I. The result is Gamma_k = I_k / I0 in (0, 1]. A particle does not
//! shade itself.
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "kiri/geometry/particles/particles.hpp"

namespace kiri::geometry {

struct HarrisStats {
    std::size_t pairs_tested = 0;  //!< occluder candidates looked at
    std::size_t occluders = 0;     //!< recurrence steps taken (footprints that cover a centre)
};

//! Gamma_k for every particle, light towards the sun (normalised here). Occluders are found
//! through a grid over the plane perpendicular to the light (cells of the largest radius), so
//! the cost is N times the particles in a column, not N^2. \throw std::invalid_argument for a
//! zero or non-finite light.
std::vector<double> harris_light_pass(const ParticleCloud& cloud, const glm::dvec3& light,
                                      HarrisStats* stats = nullptr);

//! The same by testing every pair, O(N^2): the index's oracle (equal results, bit for bit).
std::vector<double> harris_light_pass_quadratic(const ParticleCloud& cloud, const glm::dvec3& light);

}  // namespace kiri::geometry
