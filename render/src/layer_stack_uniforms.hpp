#pragma once
// The layer stack's uniforms of layers.vert ([Thesis] (2.6)-(2.10)): set by the layers pass
// each frame and by the test that reads layers.vert's vertices back against the CPU stack.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "kiri/geometry/layers/layer_stack.hpp"
#include "shader_program.hpp"

namespace kiri::render::detail {

//! Instances 0..top draw layers top..under (the layers over the eye, top first), then
//! 0..under - 1 (those under it, bottom first); `under` as geometry::layers_under_eye gives it:
//! top + 1 draws them all bottom first, 0 all top first.
void set_layer_stack_uniforms(const ShaderProgram& program, const geometry::LayerOptions& options,
                              const glm::dvec2& centre, const glm::vec3& eye, int top, int under);

}  // namespace kiri::render::detail
