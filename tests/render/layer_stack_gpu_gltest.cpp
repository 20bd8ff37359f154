// The layer stack users see is computed in layers.vert; the CPU's (layer_column, layer_vertex,
// layer_dissipation in geometry/src/layers/layer_stack.cpp) is what the exports, the reference
// and the docs use. Here layers.vert runs alone with transform feedback, under the uniforms
// the layers pass sets (set_layer_stack_uniforms), and every layer of every vertex is read back
// and compared with the CPU's to 1e-5 relative: narrowing (2.8), the real-valued count that
// keeps the thickness (2.9), enlargement (2.10), the alpha profile (2.7) and dissipation, with
// the eye far, within L0, just above a vertex and on one.
#include <epoxy/gl.h>

#include <cmath>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "kiri/geometry/layers/layer_stack.hpp"
#include "layer_stack_uniforms.hpp"
#include "render/render_fixture.hpp"
#include "shader_program.hpp"

namespace {

namespace g = kiri::geometry;
using kiri::render::detail::ShaderProgram;

struct BaseVertex {
    glm::dvec3 position, normal;
};

// A 7 x 7 patch of base vertices with heights and tilted normals that vary over it.
std::vector<BaseVertex> base_vertices()
{
    std::vector<BaseVertex> out;
    for (int j = 0; j < 7; ++j)
        for (int i = 0; i < 7; ++i) {
            const double x = -1500.0 + 500.0 * i, y = -1500.0 + 500.0 * j;
            const glm::dvec3 n = glm::normalize(glm::dvec3(0.3 * std::sin(0.002 * x), 0.4 * std::cos(0.0015 * y), 1.0));
            out.push_back({{x, y, 300.0 + 0.05 * x - 0.03 * y}, n});
        }
    return out;
}

// What layers.vert writes per vertex and instance.
struct Captured {
    float world[3];
    float alpha, exponent, spacing, height, slab, slab_above;
};

// Every layer 0..max_count of every vertex as layers.vert computes it.
std::vector<Captured> gpu_stack(const g::LayerOptions& o, const std::vector<BaseVertex>& base, const glm::dvec2& centre,
                                const glm::dvec3& eye)
{
    ShaderProgram program({"medium_shell.glsl", "light_volume.glsl", "layers.vert"});
    const char* varyings[] = {"v_world", "v_alpha", "v_exponent", "v_spacing", "v_height", "v_slab", "v_slab_above"};
    glTransformFeedbackVaryings(program.id(), 7, varyings, GL_INTERLEAVED_ATTRIBS);
    glLinkProgram(program.id());  // the varyings take effect at link time
    GLint linked = 0;
    glGetProgramiv(program.id(), GL_LINK_STATUS, &linked);
    EXPECT_EQ(linked, GL_TRUE);
    set_layer_stack_uniforms(program, o, centre, glm::vec3(eye), o.max_count, o.max_count + 1);  // instance i: layer i
    program.set("u_view_projection", glm::mat4(1.0f));

    std::vector<float> vertices;  // position, normal, atlas uv: the layers pass's layout
    for (const BaseVertex& v : base)
        for (double c : {v.position.x, v.position.y, v.position.z, v.normal.x, v.normal.y, v.normal.z, 0.0, 0.0})
            vertices.push_back(float(c));
    GLuint vao = 0, vbo = 0, feedback = 0;
    glCreateVertexArrays(1, &vao);
    glCreateBuffers(1, &vbo);
    glNamedBufferData(vbo, GLsizeiptr(vertices.size() * sizeof(float)), vertices.data(), GL_STATIC_DRAW);
    glVertexArrayVertexBuffer(vao, 0, vbo, 0, 8 * sizeof(float));
    for (GLuint a = 0; a < 3; ++a) {
        glEnableVertexArrayAttrib(vao, a);
        glVertexArrayAttribFormat(vao, a, a == 2 ? 2 : 3, GL_FLOAT, GL_FALSE, a * 3 * sizeof(float));
        glVertexArrayAttribBinding(vao, a, 0);
    }
    const std::size_t layers = std::size_t(o.max_count) + 1;
    std::vector<Captured> out(base.size() * layers);
    glCreateBuffers(1, &feedback);
    glNamedBufferData(feedback, GLsizeiptr(out.size() * sizeof(Captured)), nullptr, GL_STATIC_READ);

    // The headless context has no default framebuffer, and a draw needs a complete one even
    // with rasterisation off.
    GLuint colour = 0, framebuffer = 0;
    glCreateRenderbuffers(1, &colour);
    glNamedRenderbufferStorage(colour, GL_RGBA8, 1, 1);
    glCreateFramebuffers(1, &framebuffer);
    glNamedFramebufferRenderbuffer(framebuffer, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);

    program.use();
    glBindVertexArray(vao);
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, feedback);
    glEnable(GL_RASTERIZER_DISCARD);
    glBeginTransformFeedback(GL_POINTS);
    glDrawArraysInstanced(GL_POINTS, 0, GLsizei(base.size()), GLsizei(layers));
    glEndTransformFeedback();
    glDisable(GL_RASTERIZER_DISCARD);
    glGetNamedBufferSubData(feedback, 0, GLsizeiptr(out.size() * sizeof(Captured)), out.data());
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &framebuffer);
    glDeleteRenderbuffers(1, &colour);
    glDeleteBuffers(1, &feedback);
    glDeleteBuffers(1, &vbo);
    glDeleteVertexArrays(1, &vao);
    return out;
}

// Relative to the value, or to `scale` where the value is smaller (a fading alpha near 0).
void expect_close(double gpu, double cpu, double scale, const std::string& what)
{
    EXPECT_LE(std::abs(gpu - cpu), 1e-5 * std::max(std::abs(cpu), scale)) << what << ": gpu " << gpu << ", cpu " << cpu;
}

// The GPU's stack equals the CPU's for every vertex and layer; returns the largest count n.
double compare_stacks(const g::LayerOptions& o, const glm::dvec3& eye, const std::string& name)
{
    const std::vector<BaseVertex> base = base_vertices();
    const glm::dvec2 centre(120.0, -80.0);
    const std::vector<Captured> gpu = gpu_stack(o, base, centre, eye);
    const std::size_t layers = std::size_t(o.max_count) + 1;
    double most = 0.0;
    for (std::size_t k = 0; k < layers; ++k)
        for (std::size_t v = 0; v < base.size(); ++v) {
            const Captured& c = gpu[k * base.size() + v];
            const g::LayerColumn column = g::layer_column(o, eye, base[v].position, base[v].normal);
            const g::LayerVertex cpu = g::layer_vertex(o, column, int(k), base[v].position, centre);
            most = std::max(most, column.count);
            const std::string what = name + " vertex " + std::to_string(v) + " layer " + std::to_string(k);
            const double size = glm::length(cpu.position);
            for (int a = 0; a < 3; ++a)
                expect_close(c.world[a], cpu.position[a], size, what + " position");
            expect_close(c.alpha, cpu.alpha * g::layer_dissipation(o, int(k), column.count), 1.0, what + " alpha");
            expect_close(c.exponent, cpu.exponent, 1.0, what + " exponent r/r0");
            expect_close(c.spacing, column.spacing, 1.0, what + " spacing r");
            // The slab's optical depth goes as alpha x share; the product is continuous in n where
            // the share alone steps (at a layer that fades in from 0).
            expect_close(c.alpha * c.slab, cpu.alpha * g::layer_dissipation(o, int(k), column.count) * cpu.slab, 1.0,
                         what + " slab share");
            expect_close(c.alpha * c.slab_above,
                         cpu.alpha * g::layer_dissipation(o, int(k), column.count) * cpu.slab_above, 1.0,
                         what + " slab share above the layer");
            if (::testing::Test::HasFailure())
                return most;  // one vertex's story is enough
        }
    return most;
}

class LayerStackGpu : public kiri::test::GlTest {};

g::LayerOptions every_rule_on()
{
    g::LayerOptions o;
    o.count = 15;
    o.thickness = 200.0;  // r0 = 13.3 m, L0 = 200 r0 = 2667 m
    o.narrowing = true;
    o.enlargement = true;
    o.enlargement_rate = 0.008;           // near the most the range allows: upper layers visibly enlarged
    o.shading = g::LayerShading::source;  // the shading the enlargement is drawn in (layers_enlarge)
    o.max_count = 120;
    return o;
}

TEST_F(LayerStackGpu, FarEyeGivesTheSourceStack)
{
    const g::LayerOptions o = every_rule_on();
    // Beyond L0 from every vertex: no narrowing, l0 layers; enlargement still on.
    EXPECT_NEAR(compare_stacks(o, {9000.0, -7000.0, 4000.0}, "far"), 15.0, 1e-9);
}

TEST_F(LayerStackGpu, EyeWithinL0NarrowsAndAddsLayers)
{
    const g::LayerOptions o = every_rule_on();
    const double most = compare_stacks(o, {200.0, 300.0, 900.0}, "within L0");
    EXPECT_GT(most, 15.0 * 2.5);  // 600 m from the nearest vertex: r' <= r0 0.23 + ...
    EXPECT_LT(most, 120.0);
}

TEST_F(LayerStackGpu, EyeJustAboveAVertexReachesTheMostLayers)
{
    const g::LayerOptions o = every_rule_on();
    EXPECT_NEAR(compare_stacks(o, {0.0, 0.0, 300.0 + 2.0}, "just above"), 120.0, 1e-9);
}

TEST_F(LayerStackGpu, EyeOnAVertexIsFinite)
{
    const g::LayerOptions o = every_rule_on();
    EXPECT_NEAR(compare_stacks(o, {500.0, 500.0, 300.0 + 0.05 * 500.0 - 0.03 * 500.0}, "on a vertex"), 120.0, 1e-9);
}

TEST_F(LayerStackGpu, MediumShadingAndDissipationAsTheCpu)
{
    g::LayerOptions o = every_rule_on();
    o.shading = g::LayerShading::medium;  // the profile 1 - (1 - top_density) h, and not enlarged
    o.optics.time = 1800.0;
    o.optics.dissipation_half_life = 3600.0;
    compare_stacks(o, {-400.0, 700.0, 1200.0}, "medium shading, dissipating");
}

TEST_F(LayerStackGpu, RulesOffGiveEvenlySpacedUnscaledLayers)
{
    g::LayerOptions o = every_rule_on();
    o.narrowing = false;
    o.enlargement = false;
    EXPECT_NEAR(compare_stacks(o, {0.0, 0.0, 310.0}, "rules off"), 15.0, 1e-9);
}

}  // namespace
