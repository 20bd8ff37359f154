#pragma once
//! \file light_volume_bake.hpp
//! The bake of the light-transport volume (kiri/geometry/medium/light_volume.hpp): the sun's light
//! traced forward through the fog with the path tracer's own pieces (path_tracer.hpp: delta
//! tracking against its majorants, Henyey-Greenstein sampling, the heightfield), every segment
//! after the first scattering accumulated by a track-length estimator ([Spanier69]) into the spherical-harmonic
//! moments of the diffuse radiance.
//!
//! Photons start where the sun's light first scatters, drawn inside the fog (the Medium's shell
//! and the height fog within the Medium's box) and weighted by the density of first collisions,
//! pi sigma_t T_sun (a sun of unit radiance, irradiance pi; the terrain hides, the fog dims), over
//! the density they were drawn from: along rays of sunlight entering the box through the top of
//! each (x, y) cell and through the strips of the side faces the sun shines on, each patch's rays
//! stratified, as many as the share of the sunlight they scatter asks for, the point along a ray
//! drawn as a march of the fog's density along it says. From there they scatter in the Medium and
//! in the height fog (each with its albedo and g) until they are absorbed by the ground (black:
//! the lighting model's ground reflects nothing into the fog either), leave the box, or lose
//! Russian roulette. The single
//! scattering (the unscattered sunlight) is not in the volume: the lighting model draws it exactly.
//! Each photon draws from its own random stream seeded by (seed, photon), and the moments are
//! summed in fixed point, so the volume is bit-identical on any number of threads.
#include <cstdint>

#include <glm/vec3.hpp>

#include "kiri/geometry/medium/light_volume.hpp"
#include "kiri/geometry/reference/reference_fog.hpp"
#include "kiri/geometry/terrain/heightfield.hpp"

namespace kiri::geometry {

struct LightVolumeOptions {
    //! Photons traced, as many entering through the top of every (x, y) cell, and through the
    //! side faces as many per area seen from the sun (rounded up to whole columns); 0:
    //! photons_per_column per cell (and per such area on the sides) times the share of the
    //! sunlight its rays scatter (1 - exp(-tau) along them), at least a quarter of it (a sixteenth
    //! where they meet no fog).
    long long photons = 0;
    int photons_per_column = 300;
    //! With photons 0, at least this many in all (photons_per_column raised to reach it): a small
    //! or thin fog's few cells would otherwise carry the noise of a few thousand photons.
    long long min_photons = 200000;
    int levels = 8;  //!< cells in h between the floor and the top, [1, 64]
    int bands = 8;   //!< spherical-harmonic bands, [1, light_volume_max_bands]
    //! Cells in (x, y), metres; 0: the Medium's grid spacing or the mean free path 1 / extinction,
    //! the larger, with at most max_side cells a side (fewer where the sums would pass 2^23 a thread).
    double cell_size = 0.0;
    int max_side = 32;
    int max_bounces = 1000;  //!< scatterings a photon may have
    int roulette_after = 3;  //!< Russian roulette on the weight from this many scatterings on
    //! Store the diffuse light over the cells' mean column_scale (light_volume.hpp), so that a
    //! thin body of fog beside a thick one in the same cell does not get the thick one's light.
    bool column_normalised = true;
    std::uint64_t seed = 1;
    bool surround = true;  //!< the ground beyond the DEM's edge (path_tracer.hpp)
    int threads = 0;       //!< 0: every core
};

//! The light volume of `fog`'s Medium under a sun in `sun_direction` (towards the sun), the
//! terrain (may be null) hiding and absorbing. Empty without a Medium of positive extinction or
//! with the sun at or below the horizon.
LightVolume bake_light_volume(const FogVolume& fog, const Heightfield* terrain, const glm::dvec3& sun_direction,
                              const LightVolumeOptions& options = {});

}  // namespace kiri::geometry
