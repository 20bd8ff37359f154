#pragma once
//! \file medium_options.hpp
//! The optics of the fog (REFERENCE 6): what the scene's "medium" section sets, read by the
//! Medium (medium.hpp) and by the layers when they shade from the medium.
//! The fog's motion (detail noise, wind, time, dissipation) is the medium's too: the layers
//! read it from here, so they and the volume renderers move the same fog.
#include <glm/vec2.hpp>

namespace kiri::geometry {

struct MediumOptions {
    double extinction = 0.02;            //!< sigma_t (1/m) at density 1 (visibility 196 m: dense fog), > 0
    double albedo = 0.99;                //!< scattering / extinction, [0, 1]; fog hardly absorbs
    double anisotropy = 0.8;             //!< Henyey-Greenstein g, (-1, 1); water droplets ~0.8
    double top_density = 0.1;            //!< profile at the shell's top relative to its bottom, [0, 1] (2.7: 0.1)
    double grid_spacing = 0.0;           //!< metres between grid samples; 0 = the terrain's spacing
    int max_grid_side = 1024;            //!< the grid is coarsened to at most this many samples per side
    int scattering_octaves = 3;          //!< 1: single scattering; more: multiple scattering (fog_lighting.hpp), [1, 8]
    double detail = 0.6;                 //!< strength of the world-space noise in the density, [0, 1]
    double detail_scale = 1500.0;        //!< metres: size of the noise's largest features, > 0
    glm::dvec2 wind{0.0};                //!< m/s: drift of the noise
    double time = 0.0;                   //!< seconds since the scene's start
    double dissipation_half_life = 0.0;  //!< seconds; 0: no dissipation (the top thins faster)
    bool operator==(const MediumOptions&) const = default;
};

}  // namespace kiri::geometry
