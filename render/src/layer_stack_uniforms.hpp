#pragma once
// The layer stack's uniforms of layers.vert ([Thesis] (2.6)-(2.10)): set by the layers pass
// each frame and by the test that reads layers.vert's vertices back against the CPU stack.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "kiri/geometry/layers/layer_stack.hpp"
#include "frame_context.hpp"
#include "shader_program.hpp"

namespace kiri::render::detail {

//! Instances 0..top draw layers top..under (the layers over the eye, top first), then
//! 0..under - 1 (those under it, bottom first); `under` as geometry::layers_under_eye gives it:
//! top + 1 draws them all bottom first, 0 all top first.
void set_layer_stack_uniforms(const ShaderProgram& program, const geometry::LayerOptions& options,
                              const glm::dvec2& centre, const glm::vec3& eye, int top, int under);

//! Where the eye's rays start in the stack (layers_light.glsl's eye_region).
struct EyeInStack {
    bool inside = false;  //!< the eye lies between two layers of the stack
    double base_z = 0.0;  //!< geometry::layer_stack_under
    double spacing = 0.0;
    double reach = 0.0;  //!< metres within which a ray may still be in the space it started in
};
void set_eye_in_stack_uniforms(const ShaderProgram& program, const EyeInStack& eye);

//! The fog's optics, its detail and the frame's light (layers_light.glsl) and haze, as the
//! layers (layers.frag) and the stretch before the terrain (layers_end.frag) read them.
void set_layers_light_uniforms(const ShaderProgram& program, const geometry::LayerOptions& options,
                               const FrameContext& frame, const glm::dvec2& noise_shift);

}  // namespace kiri::render::detail
