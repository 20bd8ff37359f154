#pragma once
//! \file medium_options.hpp
//! The optics of the fog ([ValleyFog]): what the scene's "medium" section sets, read by the
//! Medium (medium.hpp) and by the layers when they shade from the medium.
//! The fog's motion (detail noise, wind, time, dissipation) is the medium's too: the layers
//! read it from here, so they and the volume renderers move the same fog.
#include <glm/vec2.hpp>

#include "kiri/geometry/core/fields.hpp"

namespace kiri::geometry {

//! How the lighting model approximates the light scattered more than once (fog_lighting.hpp).
enum class MultipleScattering {
    fitted,   //!< the model fitted to the path tracer (docs/medium.md, "Multiple scattering")
    octaves,  //!< `scattering_octaves` octaves ([Wrenninge13]); 1: single scattering
    none,     //!< single scattering only
    //! single scattering plus the light scattered more than once from a light-transport volume
    //! baked by tracing the sun's light (light_volume.hpp; docs/medium.md)
    baked,
};
inline constexpr Choice multiple_scattering_names[] = {{"fitted", int(MultipleScattering::fitted)},
                                                       {"octaves", int(MultipleScattering::octaves)},
                                                       {"none", int(MultipleScattering::none)},
                                                       {"baked", int(MultipleScattering::baked)}};

struct MediumOptions {
    double extinction = 0.02;  //!< visibility 196 m: a dense valley fog
    double albedo = 0.99;      //!< fog hardly absorbs
    double anisotropy = 0.8;   //!< water droplets
    double top_density = 0.1;  //!< (2.7): the layers' alpha at the top
    double grid_spacing = 0.0;
    int max_grid_side = 1024;
    MultipleScattering multiple_scattering = MultipleScattering::fitted;
    int scattering_octaves = 3;
    double detail = 0.6;
    double detail_scale = 1500.0;
    //! The noise's shift with height, in layers of a stack of this many (the thesis' per-layer
    //! shift; 15, the layers' default count). The fog's own, not the layers': a stack of any count
    //! draws the noise of its layers' heights.
    double detail_layers = 15.0;
    glm::dvec2 wind{0.0};
    double time = 0.0;
    double dissipation_half_life = 0.0;
    bool operator==(const MediumOptions&) const = default;
};

//! The "medium" section. visibility, liquid_water_content (with droplet_radius) are other ways
//! to give the extinction (at most one of the three).
template <fields_of<MediumOptions> O, class V>
void visit_fields(O& o, V&& v)
{
    v(o.extinction, {.key = "extinction", .unit = "1/m", .range = greater_than(0), .doc = "sigma_t at full density"});
    v(hand_written,
      {.key = "visibility",
       .unit = "m",
       .range = greater_than(0),
       .doc = "instead of `extinction`: Koschmieder visibility V, sigma = 3.912 / V",
       .widget = closed(10, 20000),
       .log_widget = true});
    v(hand_written,
      {.key = "liquid_water_content",
       .unit = "g/m^3",
       .range = greater_than(0),
       .doc = "instead of `extinction`: with `droplet_radius`, sigma = 3 Q LWC / (4 rho_w r), Q = 2"});
    v(hand_written,
      {.key = "droplet_radius",
       .unit = "um",
       .range = greater_than(0),
       .doc = "effective droplet radius, with `liquid_water_content` only",
       .shown_default = "7"});
    v(o.albedo, {.key = "albedo", .range = closed(0, 1), .doc = "scattering / extinction"});
    v(o.anisotropy,
      {.key = "anisotropy", .range = open_range(-1, 1), .doc = "Henyey-Greenstein g", .widget = closed(-0.95, 0.95)});
    v(o.top_density,
      {.key = "top_density",
       .range = closed(0, 1),
       .doc = "density at the top of the fog relative to its bottom (the layers' 0.1)"});
    v(o.grid_spacing,
      {.key = "grid_spacing",
       .unit = "m",
       .range = at_least(0),
       .doc = "between the medium's grid samples; 0 = the terrain's spacing"});
    v(o.max_grid_side,
      {.key = "max_grid_side",
       .range = closed(2, 8192),
       .doc = "the grid is coarsened to at most this many samples per side"});
    v(o.multiple_scattering,
      {.key = "multiple_scattering",
       .doc = "the light scattered more than once: fitted to the path tracer, octaves, none (single "
              "scattering), or baked (a light-transport volume traced from the sun for the scene, every "
              "renderer reads it; seconds of CPU per sun) ([medium.md](medium.md#lighting))",
       .choices = multiple_scattering_names});
    v(o.scattering_octaves,
      {.key = "scattering_octaves",
       .range = closed(1, 8),
       .doc = "with `multiple_scattering` octaves: 1 is single scattering, more approximate multiple scattering "
              "by octaves"});
    v(o.detail,
      {.key = "detail", .range = closed(0, 1), .doc = "strength of the drifting detail noise in the density"});
    v(o.detail_scale,
      {.key = "detail_scale",
       .unit = "m",
       .range = greater_than(0),
       .doc = "size of the noise's largest features (its tile repeats every 8 times that)",
       .widget = closed(100, 10000),
       .log_widget = true});
    v(o.detail_layers,
      {.key = "detail_layers",
       .range = closed(0, 1000),
       .doc = "the noise shifts by (0.137, 0.071) of its tile per 1/detail_layers of the fog's height, as the "
              "thesis' layers shift theirs (15, the layers' default count; 0: the same noise at every height); "
              "the fog's own, whatever the layers' count or the quality preset",
       .widget = closed(0, 60)});
    v(o.wind,
      {.key = "wind",
       .unit = "m/s",
       .doc = "drift of the detail noise",
       .widget = closed(-30, 30),
       .shape = "[east, north]"});
    v(o.time,
      {.key = "time",
       .unit = "s",
       .doc = "since the scene's start: the noise drifts, the fog dissipates",
       .widget = closed(0, 3600)});
    v(o.dissipation_half_life,
      {.key = "dissipation_half_life",
       .unit = "s",
       .range = at_least(0),
       .doc = "0.5^(t / half_life (1 + h)) at height fraction h: the top thins first; 0 = none",
       .widget = closed(0, 3600)});
}

}  // namespace kiri::geometry
