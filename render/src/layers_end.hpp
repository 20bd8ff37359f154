#pragma once
//! The fog a ray crosses just before the terrain, in the slab of a layer it never crosses
//! (layers_end.frag): drawn by the layers pass into its target before the stack.
#include <memory>

#include <glm/vec4.hpp>

#include "frame_context.hpp"
#include "gl_objects.hpp"
#include "kiri/geometry/layers/layer_stack.hpp"
#include "layer_stack_uniforms.hpp"
#include "render_targets.hpp"
#include "shader_program.hpp"

namespace kiri::render::detail {

class FroxelPass;
class ShadowMapPass;
class SunVolume;
class LightVolumeTexture;

class LayersEnd {
public:
    //! The base's height under each (x, y) as its triangles interpolate it, rasterised once per
    //! base (-1e30 outside it).
    void set_base(const geometry::LayerBase& base);

    struct Inputs {
        const geometry::LayerOptions& options;
        const FrameContext& frame;
        glm::dvec2 noise_shift{0.0};
        EyeInStack eye;
        GLuint noise = 0;
        unsigned resolved_depth = 0;
        //! The frame's samples (4) to draw each one's fog before its own ground into the targets of
        //! each sample's blend (layers.frag's LAYERS_AT_SAMPLES), or null.
        const FrameSamples* at_samples = nullptr;
        const FroxelPass* fog = nullptr;
        const ShadowMapPass* shadow = nullptr;
        const SunVolume* sun = nullptr;  //!< required: the Medium's grid and tau_sun
        const LightVolumeTexture* light_volume = nullptr;
    };
    //! Into the bound framebuffer (its viewport set), blended over what it holds.
    void draw(const Inputs& in);

private:
    Texture heights_;
    glm::vec4 rect_{0.0f};
    std::unique_ptr<ShaderProgram> programs_[2][2][2];  // [froxel fog][the baked light][at samples], built on first use
    VertexArray empty_vao_;
};

}  // namespace kiri::render::detail
