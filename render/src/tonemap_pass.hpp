#pragma once
#include "frame_context.hpp"
#include "shader_program.hpp"

namespace kiri::render::detail {

//! The frame's last step: linear radiance (the resolved half-float target) to the 8-bit display
//! image, with the exposure and the sRGB curve. Every pass before it works in radiance, so fog
//! blends physically (terrain * transmittance + in-scattered light) whichever pass draws it.
class ToneMapPass {
public:
    ToneMapPass();
    //! Reads `hdr_color` (a texture the size of the frame), writes the bound framebuffer.
    void draw(const FrameContext& frame, unsigned hdr_color) const;

private:
    ShaderProgram program_;
    VertexArray empty_vao_;
};

}  // namespace kiri::render::detail
