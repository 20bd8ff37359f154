#include "overlay_pass.hpp"

#include <algorithm>
#include <vector>

#include "kiri/geometry/core/error.hpp"

namespace kiri::render::detail {
namespace {

struct OverlayPassVertex {
    float position[3];
    float normal[3];
    float color[4];
};

void check(const std::string& name, const OverlayMesh& m)
{
    const std::size_t n = m.positions.size();
    const auto fail = [&](const std::string& why) { throw Error("overlay '" + name + "': " + why); };
    if (!m.normals.empty() && m.normals.size() != n)
        fail("normals must be empty or one per position");
    if (!m.colors.empty() && m.colors.size() != n)
        fail("colors must be empty or one per position");
    const std::size_t per = m.primitive == OverlayMesh::Primitive::lines ? 2 : 3;
    if (m.indices.size() % per != 0)
        fail("the index count is not a multiple of " + std::to_string(per));
    for (std::uint32_t i : m.indices)
        if (i >= n)
            fail("index " + std::to_string(i) + " is past the " + std::to_string(n) + " positions");
}

}  // namespace

OverlayPass::OverlayPass() : program_({"overlay.vert", "overlay.frag"}) {}

void OverlayPass::set(const std::string& name, const OverlayMesh& mesh)
{
    check(name, mesh);
    Entry e;
    e.style = entries_.count(name) ? entries_.at(name).style : OverlayStyle{};
    e.lines = mesh.primitive == OverlayMesh::Primitive::lines;
    e.lit = !mesh.normals.empty();
    e.index_count = GLsizei(mesh.indices.size());
    if (e.index_count > 0) {
        std::vector<OverlayPassVertex> v(mesh.positions.size());
        for (std::size_t i = 0; i < v.size(); ++i) {
            const glm::vec3 p = mesh.positions[i];
            const glm::vec3 n = e.lit ? mesh.normals[i] : glm::vec3(0.0f, 0.0f, 1.0f);
            const glm::vec4 c = mesh.colors.empty() ? glm::vec4(1.0f) : mesh.colors[i];
            v[i] = {{p.x, p.y, p.z}, {n.x, n.y, n.z}, {c.r, c.g, c.b, c.a}};
            e.min = i == 0 ? glm::dvec3(p) : glm::min(e.min, glm::dvec3(p));
            e.max = i == 0 ? glm::dvec3(p) : glm::max(e.max, glm::dvec3(p));
        }
        e.vao = make_vertex_array();
        e.vertices = make_buffer();
        e.indices = make_buffer();
        glNamedBufferStorage(e.vertices.get(), GLsizeiptr(v.size() * sizeof(OverlayPassVertex)), v.data(), 0);
        glNamedBufferStorage(e.indices.get(), GLsizeiptr(mesh.indices.size() * sizeof(std::uint32_t)),
                             mesh.indices.data(), 0);
        glVertexArrayVertexBuffer(e.vao.get(), 0, e.vertices.get(), 0, sizeof(OverlayPassVertex));
        glVertexArrayElementBuffer(e.vao.get(), e.indices.get());
        const GLint sizes[3] = {3, 3, 4};
        const GLuint offsets[3] = {offsetof(OverlayPassVertex, position), offsetof(OverlayPassVertex, normal),
                                   offsetof(OverlayPassVertex, color)};
        for (GLuint a = 0; a < 3; ++a) {
            glEnableVertexArrayAttrib(e.vao.get(), a);
            glVertexArrayAttribFormat(e.vao.get(), a, sizes[a], GL_FLOAT, GL_FALSE, offsets[a]);
            glVertexArrayAttribBinding(e.vao.get(), a, 0);
        }
    }
    entries_[name] = std::move(e);
}

void OverlayPass::set_style(const std::string& name, const OverlayStyle& style) { entries_[name].style = style; }

bool OverlayPass::has_visible() const
{
    return std::any_of(entries_.begin(), entries_.end(),
                       [](const auto& kv) { return kv.second.style.visible && kv.second.index_count > 0; });
}

void OverlayPass::extend_bounds(glm::dvec3& lo, glm::dvec3& hi) const
{
    for (const auto& [name, e] : entries_) {
        if (!e.style.visible || e.index_count == 0)
            continue;
        const bool empty = hi.x < lo.x;
        lo = empty ? e.min : glm::min(lo, e.min);
        hi = empty ? e.max : glm::max(hi, e.max);
    }
}

void OverlayPass::draw(const FrameContext& frame) const
{
    std::vector<const Entry*> order;
    for (const auto& [name, e] : entries_)  // std::map: by name
        if (e.style.visible && e.index_count > 0)
            order.push_back(&e);
    if (order.empty())
        return;
    std::stable_sort(order.begin(), order.end(),
                     [](const Entry* a, const Entry* b) { return a->style.order < b->style.order; });
    program_.set("u_view_projection", frame.view_projection);
    program_.set("u_eye", frame.eye);
    program_.set("u_sun_direction", frame.sun_direction);
    program_.use();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glDisable(GL_CULL_FACE);
    glEnable(GL_BLEND);
    // Colour blends over the frame; the frame's alpha stays opaque (read-backs are RGBA).
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
    for (const Entry* e : order) {
        program_.set("u_color", e->style.color);
        program_.set("u_lit", e->lit ? 1 : 0);
        program_.set("u_lift", e->style.lift);
        glPolygonMode(GL_FRONT_AND_BACK, e->style.wireframe ? GL_LINE : GL_FILL);
        glBindVertexArray(e->vao.get());
        glDrawElements(e->lines ? GL_LINES : GL_TRIANGLES, e->index_count, GL_UNSIGNED_INT, nullptr);
    }
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
}

}  // namespace kiri::render::detail
