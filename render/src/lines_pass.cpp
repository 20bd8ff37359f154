#include "lines_pass.hpp"

namespace kiri::render::detail {

LinesPass::LinesPass() : program_({"lines.vert", "lines.frag"}) {}

bool LinesPass::set(int slot, const std::vector<glm::dvec3>& points, const glm::vec4& color)
{
    if (slot < 0 || slot >= 8)
        return false;
    Set& s = sets_[slot];
    s.color = color;
    s.count = GLsizei(points.size() / 2 * 2);
    if (s.count == 0) {
        s.vao = {};
        s.vertices = {};
        return false;
    }
    std::vector<glm::vec3> data(points.begin(), points.begin() + s.count);
    s.vao = make_vertex_array();
    s.vertices = make_buffer();
    glNamedBufferStorage(s.vertices.get(), GLsizeiptr(data.size() * sizeof(glm::vec3)), data.data(), 0);
    glVertexArrayVertexBuffer(s.vao.get(), 0, s.vertices.get(), 0, sizeof(glm::vec3));
    glEnableVertexArrayAttrib(s.vao.get(), 0);
    glVertexArrayAttribFormat(s.vao.get(), 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(s.vao.get(), 0, 0);
    return true;
}

void LinesPass::draw(const FrameContext& frame) const
{
    bool any = false;
    for (const Set& s : sets_)
        any = any || s.count > 0;
    if (!any)
        return;
    program_.set("u_view_projection", frame.view_projection);
    program_.set("u_eye", frame.eye);
    program_.use();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    for (const Set& s : sets_) {
        if (s.count == 0)
            continue;
        program_.set("u_color", s.color);
        glBindVertexArray(s.vao.get());
        glDrawArrays(GL_LINES, 0, s.count);
    }
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
}

}  // namespace kiri::render::detail
