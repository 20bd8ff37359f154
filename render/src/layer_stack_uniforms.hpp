#pragma once
// The layer stack's uniforms of layers.vert ([Thesis] (2.6)-(2.10)): set by the layers pass
// each frame and by the test that reads layers.vert's vertices back against the CPU stack.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "kiri/geometry/layers/layer_stack.hpp"
#include "shader_program.hpp"

namespace kiri::render::detail {

//! Instances 0..top draw layers 0..top (bottom first) or top..0.
void set_layer_stack_uniforms(const ShaderProgram& program, const geometry::LayerOptions& options,
                              const glm::dvec2& centre, const glm::vec3& eye, int top, bool bottom_first);

}  // namespace kiri::render::detail
