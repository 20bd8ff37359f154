#pragma once
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "frame_context.hpp"
#include "shader_program.hpp"

namespace kiri::render::detail {

//! Overlay line sets (the preview's wireframes): each a list of segment end points and a colour,
//! depth-tested against the scene, drawn after the opaque passes.
class LinesPass {
public:
    LinesPass();
    //! Replaces set `slot` (0..7); an empty list removes it. Returns true (an upload).
    bool set(int slot, const std::vector<glm::dvec3>& segment_points, const glm::vec4& color);
    void draw(const FrameContext& frame) const;

private:
    struct Set {
        VertexArray vao;
        Buffer vertices;
        GLsizei count = 0;
        glm::vec4 color{1.0f};
    };
    ShaderProgram program_;
    Set sets_[8];
};

}  // namespace kiri::render::detail
