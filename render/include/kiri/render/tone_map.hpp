#pragma once
//! \file tone_map.hpp
//! The display curve of render/shaders/tonemap.frag on the CPU, for images made without GL (the
//! CPU reference) and for tests that predict a pixel: exponential exposure, then the sRGB
//! transfer curve (gamma 2.2). The shader reads display_exposure from the frame.
#include <cstdint>

#include "kiri/geometry/reference/reference_fog.hpp"
#include "kiri/render/image.hpp"

namespace kiri::render {

inline constexpr double display_exposure = 0.7;

//! Linear radiance to a display value in [0, 1): (1 - exp(-exposure L))^(1/2.2).
double tone_map(double radiance);
//! The 8-bit level the frame's tone map pass writes for `radiance` (rounded).
std::uint8_t tone_map_level(double radiance);
//! The CPU reference's composed radiance (reference_fog.hpp), tone-mapped as the frame is.
Image tone_mapped(const geometry::ReferenceImage& reference);

}  // namespace kiri::render
