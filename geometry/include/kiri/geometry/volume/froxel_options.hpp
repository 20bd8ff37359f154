#pragma once
//! \file froxel_options.hpp
//! Options of the froxel fog (render/, docs/froxel.md) and its depth-slice distributions, kept
//! here as plain data so that scenes can carry them and tests and benchmarks can reason about
//! the slices without a GL context.
#include <string>

#include "kiri/geometry/volume/height_fog.hpp"

namespace kiri::geometry {

//! How the depth slices of a froxel volume are spread between a near and a far depth.
enum class SliceDistribution {
    exponential,  //!< d = a (b / a)^s: equal ratios ([Wronski14], Assassin's Creed 4)
    log2,         //!< linear for the first log2_scale metres, then logarithmic ([Unreal])
    power,        //!< d = a + (b - a) s^power ([Godot]'s "detail spread")
};

struct FroxelOptions {
    int width = 160, height = 90, slices = 64;  //!< froxels across, down and in depth
    SliceDistribution distribution = SliceDistribution::exponential;
    double power = 2.0;        //!< exponent of the power distribution, > 0
    double log2_scale = 32.0;  //!< metres, > 0: where the log2 distribution turns logarithmic
    double near = 1.0;         //!< metres, > 0: the volume's first depth (standard slicing)
    double far = 0.0;          //!< metres: the volume's last depth; 0 = the far side of the scene
    //! Fog-aware slicing: each tile's slices span only the depths where its rays are in the
    //! Medium's shell (entry and exit of the rasterised shell, clipped by the terrain), so a
    //! thin layer gets all the slices instead of a fraction of one.
    bool fog_aware = true;
    bool temporal = true;         //!< Halton-jittered samples blended with the reprojected history
    double history_weight = 0.9;  //!< [0, 0.99]: weight of the (clamped) history
    int density_samples = 2;      //!< samples of the density per froxel, spread over its depth, 1..16
    int sun_steps = 12;           //!< steps of the sun's optical depth through the Medium, 1..64
    //! Fog-aware apply: steps along each pixel's own stretch of the Medium's shell, 1..256.
    int pixel_steps = 24;
    bool terrain_shadows = true;  //!< the terrain's shadow map (ESM) darkens the fog and the ground
    bool fog_shadows = true;      //!< the fog dims the sun on its way (the lighting model's tau_sun)
    int shadow_map_size = 1024;   //!< texels a side of the light-space terrain shadow map, 64..8192
    double esm_sharpness = 4.0;   //!< ESM exponent per shadow-map texel of depth, > 0
    HeightFog height_fog;         //!< optional global height fog
    bool operator==(const FroxelOptions&) const = default;
};

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
