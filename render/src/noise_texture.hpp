#pragma once
#include "gl_objects.hpp"

namespace kiri::render::detail {

//! A tileable 2D value-noise texture (three octaves, R8, repeat, linear): the fog layers'
//! detail, one texture fetch per fragment instead of hashing in the shader. Deterministic.
Texture make_noise_texture(int size = 256);

}  // namespace kiri::render::detail
