#pragma once
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "frame_context.hpp"
#include "shader_program.hpp"

namespace kiri::render::detail {

//! Overlays of the preview: line sets (wireframes), each a list of segment end points and a
//! colour, and one coloured translucent mesh (the deviation map); depth-tested against the
//! scene, drawn after the opaque passes.
class LinesPass {
public:
    LinesPass();
    //! Replaces set `slot` (0..7); an empty list removes it. Returns true (an upload).
    bool set(int slot, const std::vector<glm::dvec3>& segment_points, const glm::vec4& color);
    //! The coloured mesh overlay (one at a time): positions, RGBA colours, triangle indices.
    bool set_mesh(const std::vector<glm::dvec3>& positions, const std::vector<glm::vec4>& colors,
                  const std::vector<unsigned>& triangles);
    void draw(const FrameContext& frame) const;

private:
    ShaderProgram mesh_program_;
    VertexArray mesh_vao_;
    Buffer mesh_vertices_, mesh_indices_;
    GLsizei mesh_count_ = 0;
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
