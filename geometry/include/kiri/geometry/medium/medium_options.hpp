#pragma once
//! \file medium_options.hpp
//! The optics of the fog ([ValleyFog]): what the scene's "medium" section sets, read by the
//! Medium (medium.hpp) and by the layers when they shade from the medium.

namespace kiri::geometry {

struct MediumOptions {
    double extinction = 0.02;    //!< sigma_t (1/m) at density 1 (visibility 196 m: dense fog), > 0
    double albedo = 0.99;        //!< scattering / extinction, [0, 1]; fog hardly absorbs
    double anisotropy = 0.8;     //!< Henyey-Greenstein g, (-1, 1); water droplets ~0.8
    double top_density = 0.1;    //!< profile at the shell's top relative to its bottom, [0, 1] (2.7: 0.1)
    double grid_spacing = 0.0;   //!< metres between grid samples; 0 = the terrain's spacing
    int max_grid_side = 1024;    //!< the grid is coarsened to at most this many samples per side
    int scattering_octaves = 3;  //!< 1: single scattering; more: multiple scattering (fog_lighting.hpp), [1, 8]
    bool operator==(const MediumOptions&) const = default;
};

}  // namespace kiri::geometry
