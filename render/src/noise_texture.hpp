#pragma once
#include "gl_objects.hpp"

namespace kiri::render::detail {

//! The medium's tileable noise (geometry::fog_noise_tile) as an R8 texture (repeat, linear): the fog layers'
//! detail, one texture fetch per fragment instead of hashing in the shader. Deterministic.
Texture make_noise_texture(int size = 256);

}  // namespace kiri::render::detail
