#pragma once
//! \file froxel_options.hpp
//! Options of the froxel fog (render/, docs/froxel.md) and its depth-slice distributions, kept
//! here as plain data so that scenes can carry them and tests and benchmarks can reason about
//! the slices without a GL context.
#include <string>

#include "kiri/geometry/core/fields.hpp"
#include "kiri/geometry/volume/height_fog.hpp"

namespace kiri::geometry {

//! How the depth slices of a froxel volume are spread between a near and a far depth.
enum class SliceDistribution {
    exponential,  //!< d = a (b / a)^s: equal ratios ([Wronski14], Assassin's Creed 4)
    log2,         //!< linear for the first log2_scale metres, then logarithmic ([Unreal])
    power,        //!< d = a + (b - a) s^power ([Godot]'s "detail spread")
};
inline constexpr Choice slice_distribution_names[] = {{"exponential", int(SliceDistribution::exponential)},
                                                      {"log2", int(SliceDistribution::log2)},
                                                      {"power", int(SliceDistribution::power)}};

struct FroxelOptions {
    int width = 160, height = 90, slices = 64;
    SliceDistribution distribution = SliceDistribution::exponential;
    double power = 2.0;
    double log2_scale = 32.0;
    double near = 1.0;
    double far = 0.0;  //!< 0 = the far side of the scene
    //! Fog-aware slicing: each tile's slices span only the depths where its rays are in the
    //! Medium's shell (entry and exit of the rasterised shell, clipped by the terrain), so a
    //! thin layer gets all the slices instead of a fraction of one.
    bool fog_aware = true;
    bool temporal = true;
    double history_weight = 0.9;
    int density_samples = 2;
    int sun_steps = 12;
    //! tau_sun from the sun volume (built once per sun, Medium and time, shared with the
    //! layers); false: each froxel marches it in sun_steps steps for each lighting sample.
    bool sun_volume = true;
    int pixel_steps = 24;  //!< fog-aware apply
    //! Fog-aware apply: the pixels march at every eighth pixel of every eighth row, then every
    //! fourth and second; a point between marched ones takes their mean where its estimated error
    //! is at most this share of its colour through the fog (a share as fine as its grid is
    //! coarse on the coarser grids) and its depths lie within theirs (docs/froxel.md); 0: every
    //! pixel that the volume does not resolve marches its own ray.
    double upsample = 0.02;
    bool terrain_shadows = true;
    bool fog_shadows = true;
    int shadow_map_size = 1024;
    double esm_sharpness = 4.0;
    HeightFog height_fog;  //!< optional global height fog
    bool operator==(const FroxelOptions&) const = default;
};

//! The "froxel" section; far is 0 or beyond near.
template <fields_of<FroxelOptions> O, class V>
void visit_fields(O& o, V&& v)
{
    constexpr std::string_view size = "[width, height, slices]";
    v(o.width,
      {.key = "size",
       .range = closed(1, 1024),
       .doc = "froxels across, down and in depth",
       .widget = closed(16, 512),
       .element = 0,
       .elements = 3,
       .shape = size});
    v(o.height,
      {.key = "size",
       .range = closed(1, 1024),
       .doc = "froxels down",
       .widget = closed(9, 288),
       .element = 1,
       .elements = 3,
       .shape = size});
    v(o.slices,
      {.key = "size",
       .range = closed(2, 512),
       .doc = "depth slices",
       .widget = closed(8, 256),
       .element = 2,
       .elements = 3,
       .shape = size});
    v(o.distribution,
      {.key = "distribution",
       .doc = "depth slices: `exponential` (equal ratios, AC4), `log2` (Unreal: linear for "
              "`log2_scale` metres, then logarithmic), `power` (Godot: d = a + (b - a) s^power)",
       .choices = slice_distribution_names});
    v(o.power,
      {.key = "power",
       .range = left_open(0, 16),
       .doc = "exponent of the power distribution",
       .widget = closed(0.25, 8),
       .log_widget = true});
    v(o.log2_scale,
      {.key = "log2_scale",
       .unit = "m",
       .range = greater_than(0),
       .doc = "where the log2 distribution turns logarithmic",
       .widget = closed(1, 2000),
       .log_widget = true});
    v(o.near, {.key = "near", .unit = "m", .range = greater_than(0), .doc = "the volume's first depth"});
    v(o.far, {.key = "far", .unit = "m", .range = at_least(0), .doc = "its last depth; 0 = the far side of the scene"});
    v(o.fog_aware,
      {.key = "fog_aware",
       .doc = "slices where the Medium is (per-tile ranges from the rasterised shell) and each pixel's "
              "own stretch of the shell; false: the classic froxel volume over [near, far]"});
    v(o.temporal,
      {.key = "temporal",
       .doc = "Halton-jittered lighting: a sample a frame blended with the reprojected, clamped "
              "history while the view moves, a still's first 2 at once"});
    v(o.history_weight, {.key = "history_weight", .range = closed(0, 0.99), .doc = "weight of that history"});
    v(o.density_samples,
      {.key = "density_samples", .range = closed(1, 16), .doc = "density samples per froxel, spread over its depth"});
    v(o.sun_steps,
      {.key = "sun_steps",
       .range = closed(1, 64),
       .doc = "steps of the sun's optical depth through the Medium where it is marched (sun_volume false)"});
    v(o.sun_volume,
      {.key = "sun_volume",
       .doc = "tau_sun read from the sun volume that the layers read too, built once per sun, Medium and time"});
    v(o.pixel_steps,
      {.key = "pixel_steps",
       .range = closed(1, 256),
       .doc =
           "fog-aware, the eye outside the Medium's shell: steps along each pixel's stretch of it (from inside, each ray marches the volume's slices)"});
    v(o.upsample,
      {.key = "upsample",
       .range = closed(0, 1),
       .doc =
           "fog-aware: the pixels march at every eighth, then every fourth and second pixel and row; a point between "
           "marched ones takes their mean where its estimated error is at most this share of its colour through "
           "the fog and its depths lie within theirs; 0: every pixel the volume does not resolve marches",
       .widget = closed(0, 0.1)});
    v(o.terrain_shadows,
      {.key = "terrain_shadows",
       .doc = "the terrain's sun shadow map shades the ground and every fog renderer (froxels, layers, particles)"});
    v(o.fog_shadows, {.key = "fog_shadows", .doc = "the fog dims the sun on its way (tau_sun)"});
    v(o.shadow_map_size,
      {.key = "shadow_map_size", .unit = "texels", .range = closed(64, 8192), .doc = "a side of the sun's shadow map"});
    v(o.esm_sharpness,
      {.key = "esm_sharpness", .range = left_open(0, 64), .doc = "ESM exponent per shadow-map texel of depth"});
    v(hand_written,
      {.key = "height_fog",
       .doc = "global exponential height fog (the table below); `kiri render` limits it to the "
              "terrain's extent",
       .shown_default = "none",
       .type = "object"});
}

//! \throw InputError(label, "/froxel/<key>", reason) for options out of range.
void validate_froxel_options(const FroxelOptions& options, const std::string& label = {});

//! The depth of slice coordinate s in [0, 1] between depths a and b (0 < a < b).
double slice_depth(const FroxelOptions& options, double s, double a, double b);
//! The inverse of slice_depth: s in [0, 1] for a depth in [a, b] (clamped outside).
double slice_coordinate(const FroxelOptions& options, double depth, double a, double b);

//! "exponential", "log2", "power"; parse returns false for other names.
const char* to_string(SliceDistribution d);
bool parse_slice_distribution(const std::string& name, SliceDistribution& out);

}  // namespace kiri::geometry
