#pragma once
// The tests' probes of what a shader library gives at given points (the sun volume's tau_sun, the
// baked light, the terrain's shadow): a compute program with the points in storage buffer 0, one
// float per point out in buffer 1, u_count, 64 points a work group; the floats read back.
#include <cstddef>
#include <vector>

#include "shader_program.hpp"

namespace kiri::render::detail {

//! Runs `program` (its other uniforms and textures already bound) over `count` points whose
//! `bytes` of input lie at `input`, and returns its `count` floats.
std::vector<float> run_point_probe(const ShaderProgram& program, const void* input, std::size_t bytes,
                                   std::size_t count);

}  // namespace kiri::render::detail
