#pragma once
//! \file fog_target.hpp
//! Target heights of the fog base surface: the blanket follows the terrain smoothed
//! at a length scale, the lake is a flat altitude ([ValleyFog]: a valley fog's top is flat).
#include "kiri/geometry/terrain/heightfield.hpp"

namespace kiri::geometry {

//! The heightfield smoothed by a Gaussian of standard deviation sigma metres, approximated by
//! three passes of a box filter along x then y ([Wells86]; the variance of three boxes of
//! width w is 3 (w^2 - 1) / 12 cells^2, w chosen per axis from sigma / dx and sigma / dy).
//! Only valid samples contribute (normalised convolution), so nodata fill values and the
//! grid's border do not bias the result. sigma <= 0 returns a copy. Cost O(nx ny), whatever
//! sigma.
Heightfield smooth_heightfield(const Heightfield& heightfield, double sigma);

//! Bilinear interpolation of the grid at local (x, y), clamped to the grid.
double sample_bilinear(const Heightfield& heightfield, double x, double y);

//! True when the four samples around (x, y) all had data in the source.
bool has_data(const Heightfield& heightfield, double x, double y);

}  // namespace kiri::geometry
