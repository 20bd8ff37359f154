#pragma once
#include <map>
#include <string>

#include <glm/vec3.hpp>

#include "frame_context.hpp"
#include "kiri/render/overlay_mesh.hpp"
#include "shader_program.hpp"

namespace kiri::render::detail {

//! Overlay meshes (overlay_mesh.hpp), each uploaded once when set, drawn blended into the
//! bound framebuffer after everything else.
class OverlayPass {
public:
    OverlayPass();
    //! \throw kiri::Error naming the overlay when its arrays disagree (sizes, indices).
    void set(const std::string& name, const OverlayMesh& mesh);
    void set_style(const std::string& name, const OverlayStyle& style);
    void remove(const std::string& name) { entries_.erase(name); }
    bool has_visible() const;
    //! Grows (lo, hi) to hold every visible overlay (the frame's near and far planes).
    void extend_bounds(glm::dvec3& lo, glm::dvec3& hi) const;
    void draw(const FrameContext& frame) const;

private:
    struct Entry {
        VertexArray vao;
        Buffer vertices, indices;
        GLsizei index_count = 0;
        bool lines = false, lit = false;
        OverlayStyle style;
        glm::dvec3 min{0.0}, max{-1.0};
    };
    ShaderProgram program_;
    std::map<std::string, Entry> entries_;
};

}  // namespace kiri::render::detail
