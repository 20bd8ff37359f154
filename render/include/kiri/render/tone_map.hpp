#pragma once
//! \file tone_map.hpp
//! The display curve of render/shaders/tonemap.frag on the CPU, for images made without GL (the
//! CPU reference) and for tests that predict a pixel: exponential exposure, then the sRGB
//! transfer curve (gamma 2.2). The shader reads display_exposure from the frame.
#include <cstdint>

#include "kiri/geometry/reference/path_tracer.hpp"
#include "kiri/geometry/reference/reference_fog.hpp"
#include "kiri/render/image.hpp"

namespace kiri::render {

inline constexpr double display_exposure = 0.7;

//! Linear radiance to a display value in [0, 1): (1 - exp(-exposure L))^(1/2.2).
double tone_map(double radiance);
//! The 8-bit level the frame's tone map pass writes for `radiance` (rounded).
std::uint8_t tone_map_level(double radiance);
//! The linear radiance an 8-bit level of the frame stands for: tone_map inverted (255 is read as
//! 254.5, so that it stays finite).
double level_radiance(double level);
//! A tone-mapped picture read back as linear radiance at the pixel centres of a coarser
//! width x height image of the same view (for judging a PNG against the CPU reference at a
//! small size): each centre's value is the mean radiance of the one picture pixel there (the
//! scale odd) or of the four around it (even). \throw kiri::Error unless the picture's size is
//! a whole multiple of width x height, the same in both directions.
RadianceImage radiance_at(const Image& picture, int width, int height);
//! The CPU reference's composed radiance (reference_fog.hpp), tone-mapped as the frame is.
Image tone_mapped(const geometry::ReferenceImage& reference);
//! The path tracer's radiance (path_tracer.hpp), tone-mapped as the frame is.
Image tone_mapped(const geometry::PathTracedImage& image);
//! The linear radiance of the CPU images (alpha 1), for write_exr_atomic: the reference's
//! composed radiance, the path tracer's radiance.
RadianceImage linear_radiance(const geometry::ReferenceImage& reference);
RadianceImage linear_radiance(const geometry::PathTracedImage& image);

}  // namespace kiri::render
