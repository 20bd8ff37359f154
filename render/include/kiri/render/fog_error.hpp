#pragma once
//! \file fog_error.hpp
//! How far a GPU fog is from the CPU reference (geometry/reference_fog.hpp): both composed over
//! the reference's background (what the fog does to the picture), per pixel the relative error
//! of luminance, over the pixels the fog changes by more than 1 %.
#include <cmath>
#include <vector>

#include <glm/vec2.hpp>

#include "kiri/geometry/reference/reference_fog.hpp"
#include "kiri/render/image.hpp"
#include "kiri/render/renderer.hpp"

namespace kiri::render {

struct FogError {
    double mean_relative = 0.0;  //!< mean of |Y - Y_ref| / Y_ref over the fog pixels
    double p99_relative = 0.0;   //!< the worst 1 % of the fog pixels are at least this far off
    double worst_relative = 0.0;
    double mean_transmittance_error = 0.0;  //!< mean |T - T_ref| over the fog pixels
    double mean_inscatter_relative = 0.0;   //!< the fog alone: mean |Y_in - Y_in,ref| / Y_in,ref
    int fog_pixels = 0;                     //!< pixels compared: the reference's fog changes them by > 1 %
    int silhouette_pixels = 0;              //!< left out: the two see different surfaces (depths differ > 1 %)
};

//! Over the pixels whose reference surface lies between view depths min_depth and max_depth
//! (sky: +inf). \throw kiri::Error when the sizes differ.
FogError compare_fog(const FogBuffer& gpu, const geometry::ReferenceImage& reference, double min_depth = 0.0,
                     double max_depth = HUGE_VAL);

//! Any renderer (layers, particles, froxels, combined) judged by its whole frame: `with_fog` and
//! `without_fog` are the same view's linear radiance (Renderer::read_radiance) drawn with and
//! without the fog; the reference's fog is composed over the GPU's own background, so both
//! differ only by their fog: Y_ref = Y(shaded) T_ref + Y(S_ref), where Y(shaded) is the frame
//! without fog in the fog's shade. With `without_sun` (the frame without fog and without the
//! sun: the ground's sky light) the sun's part of the frame is dimmed by the reference's
//! ground_sun, Y(shaded) = Y(without_sun) + ground_sun (Y(without) - Y(without_sun)), which
//! keeps the GPU's own ground (its normals, its samples); without it the reference's fog_shade
//! is taken from Y(without), which leaves the two grounds' differences in the shade. Over the
//! pixels the reference's fog changes by more than 1 % (no silhouette test; the transmittance
//! and in-scatter errors are not separable from a frame and stay 0). `signed_error`, when
//! given, receives per pixel (Y - Y_ref) / Y_ref, NaN where the pixel is not judged: the error's
//! map. \throw kiri::Error when the sizes differ.
//!
//! A pixel whose footprint holds two surfaces (a ridge against the fogged valley behind it) is
//! not one ray: a multisampled frame's pixel is the mean of its samples, each of which the fog
//! should cover as far as its own surface. With `at_samples`, the reference at those pixels is
//! the mean over the frame's samples of each one's luminance composed over that sample of the
//! frames without fog: the exact fog over the GPU's own samples.
struct SampleReference;
FogError compare_frames(const RadianceImage& with_fog, const RadianceImage& without_fog,
                        const geometry::ReferenceImage& reference, std::vector<float>* signed_error = nullptr,
                        const RadianceImage* without_sun = nullptr, const SampleReference* at_samples = nullptr);

//! The pixels of `reference` whose footprint may hold more than one surface: along a row, a
//! column or a diagonal through the pixel, the view depths of its neighbours and its own do not
//! lie on a line (second difference above `bend` times its depth: a surface's smooth slope
//! passes, a ridge against the valley behind it does not), or one of them is the sky and
//! another the terrain; or where the fog bends so within it: the second difference of its
//! transmittance above `fog_bend`, or that of its in-scattered luminance above `fog_bend` times
//! the pixel's luminance (a thread of fog narrower than a pixel, the fog's top meeting a slope,
//! its side wall; 0: not judged). Row-major indices, ascending.
std::vector<std::size_t> footprint_edges(const geometry::ReferenceImage& reference, double bend = 0.01,
                                         double fog_bend = 0.05);

//! The reference through the samples of a multisampled frame's `pixels`, and those samples of
//! the frames without fog (and without the sun).
struct SampleReference {
    std::vector<std::size_t> pixels;     //!< row-major indices of the frame's pixels
    geometry::ReferenceImage reference;  //!< one row: pixel i's sample s at i * samples + s
    const RadianceSamples* without_fog = nullptr;
    const RadianceSamples* without_sun = nullptr;  //!< or null (compare_frames' without_sun)
};

//! The image points (geometry::ReferenceView::ray_through) of the samples of `pixels` of a
//! frame whose samples lie at `samples`' offsets: pixel i's sample s at i * samples + s.
std::vector<glm::dvec2> sample_points(const std::vector<std::size_t>& pixels, const RadianceSamples& samples);

//! compare_frames' reference luminance at pixel k over the frame without fog of luminance
//! y_without_fog there (and without the sun, y_without_sun; negative: not drawn).
double reference_luminance(const geometry::ReferenceImage& reference, std::size_t k, double y_without_fog,
                           double y_without_sun = -1.0);

//! A signed error map as a picture: white where it is 0, red where kiri is brighter than the
//! reference, blue where darker, full colour at +-`full_scale`; grey where not judged (NaN).
Image error_map(const std::vector<float>& signed_error, int width, int height, double full_scale = 0.2);

}  // namespace kiri::render
