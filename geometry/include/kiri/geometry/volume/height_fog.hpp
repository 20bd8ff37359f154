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

#include "kiri/geometry/core/fields.hpp"

namespace kiri::geometry {

struct HeightFog {
    double extinction = 0.0;  //!< 0: no height fog
    double base = 0.0;        //!< world z
    double scale_height = 100.0;
    double albedo = 0.99;
    double anisotropy = 0.6;
    glm::dvec2 min{-std::numeric_limits<double>::infinity()};  //!< horizontal extent (x, y)
    glm::dvec2 max{std::numeric_limits<double>::infinity()};

    bool enabled() const { return extinction > 0.0; }
    //! Its top: the base plus 8 scale heights, above which e^-8 of the base's density is left (the
    //! froxels' slices and the baked light's cells reach up to it; froxel_light.glsl lights under it).
    double top() const { return base + 8.0 * scale_height; }
    //! sigma_t (1/m) at altitude z, inside the extent.
    double sigma(double z) const;
    //! sigma_t (1/m) at p: 0 outside the extent.
    double sigma(const glm::dvec3& p) const;
    //! The integral of sigma_t along origin + t dir for t in [t0, t1] (dir need not be unit;
    //! t1 may be +inf when dir.z > 0). Exact, no cancellation for nearly level segments.
    double optical_depth(const glm::dvec3& origin, const glm::dvec3& dir, double t0, double t1) const;
    //! The inverse of optical_depth: the t in [t0, t1] where optical_depth(origin, dir, t0, t)
    //! reaches `depth` (> 0), or +inf where the segment holds less (a free path of the height fog,
    //! [Woodcock65]'s variate inverted exactly). In closed form piece by piece (the constant part
    //! under the base, the exponential above it), relative to each piece's start, so a level ray
    //! and a fog that underflows above its base stay exact (height_fog_free_path.cpp).
    double free_path(const glm::dvec3& origin, const glm::dvec3& dir, double t0, double t1, double depth) const;
    bool operator==(const HeightFog&) const = default;
};

//! The "height_fog" object of the "froxel" section; visibility is another way to give the extinction.
template <fields_of<HeightFog> O, class V>
void visit_fields(O& o, V&& v)
{
    v(o.extinction,
      {.key = "extinction",
       .unit = "1/m",
       .range = closed(0, 1000),
       .doc = "sigma_t at and below `base`; 0: no height fog"});
    v(hand_written,
      {.key = "visibility",
       .unit = "m",
       .range = greater_than(0),
       .doc = "instead of `extinction`: the Koschmieder visibility at the base",
       .widget = closed(100, 200000),
       .log_widget = true});
    v(o.base,
      {.key = "base", .unit = "m", .doc = "of the DEM (stretched by the exaggeration): where the falloff starts"});
    v(o.scale_height,
      {.key = "scale_height",
       .unit = "m",
       .range = greater_than(0),
       .doc = "of the DEM (stretched by the exaggeration): the density falls by e every scale_height",
       .widget = closed(10, 5000),
       .log_widget = true});
    v(o.albedo, {.key = "albedo", .range = closed(0, 1), .doc = "scattering / extinction"});
    v(o.anisotropy, {.key = "anisotropy", .range = open_range(-1, 1), .doc = "Henyey-Greenstein g"});
}

//! \throw InputError(label, "/froxel/height_fog/<key>", reason) for values out of range.
void validate_height_fog(const HeightFog& fog, const std::string& label = {});

}  // namespace kiri::geometry
