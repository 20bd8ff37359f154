#pragma once
#include "frame_context.hpp"
#include "shader_program.hpp"

namespace kiri::render::detail {

//! Background: sky gradient and sun glow, drawn first without depth.
class SkyPass {
public:
    SkyPass();
    void draw(const FrameContext& frame) const;

private:
    ShaderProgram program_;
    VertexArray empty_vao_;
};

}  // namespace kiri::render::detail
