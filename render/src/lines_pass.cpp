#include "lines_pass.hpp"

namespace kiri::render::detail {

LinesPass::LinesPass()
    : mesh_program_({"overlay_mesh.vert", "overlay_mesh.frag"}), program_({"lines.vert", "lines.frag"})
{
}

bool LinesPass::set_mesh(const std::vector<glm::dvec3>& positions, const std::vector<glm::vec4>& colors,
                         const std::vector<unsigned>& triangles)
{
    mesh_count_ = positions.size() == colors.size() ? GLsizei(triangles.size() / 3 * 3) : 0;
    if (mesh_count_ == 0) {
        mesh_vao_ = {};
        return false;
    }
    struct Vertex {
        glm::vec3 p;
        glm::vec4 c;
    };
    std::vector<Vertex> data(positions.size());
    for (std::size_t i = 0; i < data.size(); ++i)
        data[i] = {glm::vec3(positions[i]), colors[i]};
    mesh_vao_ = make_vertex_array();
    mesh_vertices_ = make_buffer();
    mesh_indices_ = make_buffer();
    glNamedBufferStorage(mesh_vertices_.get(), GLsizeiptr(data.size() * sizeof(Vertex)), data.data(), 0);
    glNamedBufferStorage(mesh_indices_.get(), GLsizeiptr(std::size_t(mesh_count_) * sizeof(unsigned)), triangles.data(), 0);
    glVertexArrayVertexBuffer(mesh_vao_.get(), 0, mesh_vertices_.get(), 0, sizeof(Vertex));
    glVertexArrayElementBuffer(mesh_vao_.get(), mesh_indices_.get());
    glEnableVertexArrayAttrib(mesh_vao_.get(), 0);
    glVertexArrayAttribFormat(mesh_vao_.get(), 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(mesh_vao_.get(), 0, 0);
    glEnableVertexArrayAttrib(mesh_vao_.get(), 1);
    glVertexArrayAttribFormat(mesh_vao_.get(), 1, 4, GL_FLOAT, GL_FALSE, sizeof(glm::vec3));
    glVertexArrayAttribBinding(mesh_vao_.get(), 1, 0);
    return true;
}

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
    bool any = mesh_count_ > 0;
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
    if (mesh_count_ > 0) {
        mesh_program_.set("u_view_projection", frame.view_projection);
        mesh_program_.set("u_eye", frame.eye);
        mesh_program_.use();
        glEnable(GL_BLEND);
        glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
        glBindVertexArray(mesh_vao_.get());
        glDrawElements(GL_TRIANGLES, mesh_count_, GL_UNSIGNED_INT, nullptr);
        glDisable(GL_BLEND);
    }
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
}

}  // namespace kiri::render::detail
