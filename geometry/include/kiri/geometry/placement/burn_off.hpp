#pragma once
//! \file burn_off.hpp
//! Burn-off of valley fog after sunrise ([ValleyFog]): the sun thins the fog from
//! its thin edges and from sunlit slopes first, then surface heating lifts its base and the
//! fog turns into low stratus.
#include <string>

#include <glm/vec3.hpp>

#include "kiri/geometry/core/fields.hpp"
#include "kiri/geometry/placement/fog_columns.hpp"
#include "kiri/geometry/terrain/heightfield.hpp"

namespace kiri::geometry {

//! Unit vector towards the sun (x east, y north, z up) at a latitude (degrees), day of the
//! year (1..366) and local solar time (hours): declination 23.44 sin(2 pi (284 + day) / 365)
//! degrees ([Cooper69]), hour angle 15 (hour - 12) degrees. z < 0 when the sun is down.
glm::dvec3 sun_direction(double latitude_deg, int day_of_year, double solar_hour);

struct BurnOffOptions {
    double time = 9.0;
    int day_of_year = 300;  //!< late October, the valley-fog season
    double latitude = 45.0;
    //! Metres of fog thickness evaporated from below per hour by full sun on ground facing it,
    //! as it reaches the ground through the fog.
    double burn_rate = 120.0;
    //! Metres per hour the lifted base (a flat level, from the lowest fog bottom) rises per hour
    //! of full sun on level ground: the heated, mixed air under the fog.
    double lift_rate = 60.0;
    double extinction = 0.02;  //!< sigma (1/m) of the fog, > 0 (a scene takes its medium's)
    double anisotropy = 0.8;   //!< Henyey-Greenstein g of the droplets, [0, 1) (the medium's)
    double min_thickness = 1.0;
    double step_minutes = 10.0;
    bool operator==(const BurnOffOptions&) const = default;
};

//! The "burn_off" object of the scene's "fog" section (the optics are the medium's).
template <fields_of<BurnOffOptions> O, class V>
void visit_fields(O& o, V&& v)
{
    v(o.time,
      {.key = "time",
       .unit = "h",
       .range = closed(0, 24),
       .doc = "local solar time at which to show the fog",
       .required = "missing: the local solar time (hours) at which to show the fog"});
    v(o.day_of_year,
      {.key = "day_of_year", .range = closed(1, 366), .doc = "300: late October, the valley-fog season"});
    v(o.latitude,
      {.key = "latitude",
       .unit = "deg",
       .range = closed(-90, 90),
       .doc = "north (45 when the DEM has no CRS)",
       .shown_default = "the DEM's centre"});
    v(o.burn_rate,
      {.key = "burn_rate",
       .unit = "m/h",
       .range = closed(0, 1e5),
       .doc = "of fog evaporated from below per hour of full sun on ground facing it"});
    v(o.lift_rate,
      {.key = "lift_rate",
       .unit = "m/h",
       .range = closed(0, 1e5),
       .doc = "the base lifts per hour of full sun on level ground"});
    v(o.min_thickness,
      {.key = "min_thickness", .unit = "m", .range = at_least(0), .doc = "thinner fog counts as gone"});
    v(o.step_minutes, {.key = "step_minutes", .unit = "min", .range = left_open(0, 120), .doc = "integration step"});
}

struct BurnOffReport {
    double sunrise_hour = 0.0;       //!< first step with the sun above the horizon (24 if none)
    double sun_elevation_deg = 0.0;  //!< at `time`
    double lifted_base = 0.0;        //!< altitude of the lifted base at `time` (metres)
    double sun_hours_level = 0.0;    //!< integral of max(0, sun z) from midnight to `time` (hours)
    std::size_t cells_before = 0, cells_after = 0;
    double volume_before_m3 = 0.0, volume_after_m3 = 0.0;
};

//! The fog at options.time, from the fog at dawn (`dawn`). Per cell, from midnight, with fixed
//! steps: the ground under the fog is heated by the sun through it, and evaporates it from
//! below at burn_rate * max(0, n . s) * T(h), T(h) = 1 / (1 + 3/4 (1 - g) sigma h) the diffuse
//! transmission of a scattering layer of thickness h (two-stream, [Bohren87]), n the ground's
//! normal, s the sun: thin edges (small h) and slopes facing the sun clear first. The base is
//! also held at or above the lifted level L = lowest bottom + lift_rate * sun_hours_level, so
//! the fog detaches from the valley floors as the morning goes on. The top stays. Thickness
//! never grows with time (monotone), the same inputs give the same bytes.
//! \throw InputError(label, "burn_off/<key>", reason) for options out of range.
FogColumns burn_off(const Heightfield& terrain, const FogColumns& dawn, const BurnOffOptions& options,
                    BurnOffReport* report = nullptr, const std::string& label = {});

}  // namespace kiri::geometry
