#pragma once
#include "frame_context.hpp"
#include "shader_program.hpp"

namespace kiri::render::detail {

//! Background: sky gradient and sun glow, drawn first without depth.
class SkyPass {
public:
    SkyPass();
    //! `fog` (may be null): the froxel fog seen against the sky (froxel_apply.glsl).
    void draw(const FrameContext& frame, const class FroxelPass* fog = nullptr) const;

private:
    ShaderProgram program_;
    VertexArray empty_vao_;
};

}  // namespace kiri::render::detail
