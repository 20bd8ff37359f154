#pragma once
#include "frame_context.hpp"
#include "shader_program.hpp"

namespace kiri::render::detail {

class TerrainPass;

//! Background: sky gradient and sun glow, and below the horizon the flat ground beyond the
//! terrain's surround (none without a terrain), drawn first without depth.
class SkyPass {
public:
    SkyPass();
    void draw(const FrameContext& frame, const TerrainPass& terrain) const;

private:
    ShaderProgram program_;
    VertexArray empty_vao_;
};

}  // namespace kiri::render::detail
