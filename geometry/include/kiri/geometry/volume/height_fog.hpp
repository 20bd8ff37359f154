#pragma once
//! \file height_fog.hpp
//! Global exponential height fog, the optional haze every volume renderer can add to the
//! Medium: sigma_t(z) = extinction exp(-(z - base) / scale_height) above `base` and
//! `extinction` below it (so it stays bounded under the base), over a horizontal extent (all
//! of it by default; kiri render gives it the terrain's, so no haze hangs beyond the ground).
//! Its optical depth along a straight segment has a closed form, which the froxel pass and the
//! reference both use.
#include <limits>
#include <string>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace kiri::geometry {

struct HeightFog {
    double extinction = 0.0;                                   //!< sigma_t (1/m) at and below `base`; 0: no height fog
    double base = 0.0;                                         //!< world z (m) where the falloff starts
    double scale_height = 100.0;                               //!< m, > 0: the density falls by e every scale_height
    double albedo = 0.99;                                      //!< [0, 1]
    double anisotropy = 0.6;                                   //!< Henyey-Greenstein g, (-1, 1)
    glm::dvec2 min{-std::numeric_limits<double>::infinity()};  //!< horizontal extent (x, y)
    glm::dvec2 max{std::numeric_limits<double>::infinity()};

    bool enabled() const { return extinction > 0.0; }
    //! sigma_t (1/m) at altitude z, inside the extent.
    double sigma(double z) const;
    //! sigma_t (1/m) at p: 0 outside the extent.
    double sigma(const glm::dvec3& p) const;
    //! The integral of sigma_t along origin + t dir for t in [t0, t1] (dir need not be unit;
    //! t1 may be +inf when dir.z > 0). Exact, no cancellation for nearly level segments.
    double optical_depth(const glm::dvec3& origin, const glm::dvec3& dir, double t0, double t1) const;
    bool operator==(const HeightFog&) const = default;
};

//! \throw InputError(label, "/froxel/height_fog/<key>", reason) for values out of range.
void validate_height_fog(const HeightFog& fog, const std::string& label = {});

}  // namespace kiri::geometry
