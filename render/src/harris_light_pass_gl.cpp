// Harris's light pass on the GPU, the way Harris & Lastra ran it: the speed anchor that the
// attenuation buffer is measured against (Shimada's Table 1 "Harris").
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>

#include <glm/geometric.hpp>

#include "gl_objects.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/render/attenuation.hpp"
#include "shader_program.hpp"

namespace kiri::render {

using namespace detail;

std::vector<float> harris_light_pass_gl(const geometry::ParticleCloud& cloud, const glm::dvec3& light, int buffer_size,
                                        HarrisGlStats* stats)
{
    const auto start = std::chrono::steady_clock::now();
    const std::vector<geometry::Particle>& P = cloud.particles;
    const std::size_t n = P.size();
    std::vector<float> gamma(n, 1.0f);
    if (n == 0)
        return gamma;
    const double len = glm::length(light);
    if (!(len > 0.0) || !std::isfinite(len))
        throw Error("harris_light_pass_gl: the light direction must be finite and not zero");
    // The light frame of harris_reference.cpp.
    const glm::dvec3 l = light / len;
    const glm::dvec3 side = glm::cross(glm::dvec3(0.0, 0.0, 1.0), l);
    const glm::dvec3 u = glm::length(side) > 1e-9 ? glm::normalize(side) : glm::dvec3(1.0, 0.0, 0.0);
    const glm::dvec3 v = glm::normalize(glm::cross(l, u));
    std::vector<double> pu(n), pv(n), height(n);
    glm::dvec2 lo(1e300), hi(-1e300);
    double r_min = 1e300;
    for (std::size_t k = 0; k < n; ++k) {
        pu[k] = glm::dot(u, P[k].position);
        pv[k] = glm::dot(v, P[k].position);
        height[k] = glm::dot(l, P[k].position);
        lo = glm::min(lo, glm::dvec2(pu[k] - P[k].radius, pv[k] - P[k].radius));
        hi = glm::max(hi, glm::dvec2(pu[k] + P[k].radius, pv[k] + P[k].radius));
        r_min = std::min(r_min, P[k].radius);
    }
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return height[a] > height[b] || (height[a] == height[b] && a < b); });
    // Square pixels of a quarter of the smallest radius, at most 2048 on the longer side.
    const glm::dvec2 extent = hi - lo;
    double pixel = std::max(r_min / 4.0, std::max(extent.x, extent.y) / 2048.0);
    if (buffer_size > 0)
        pixel = std::max(extent.x, extent.y) / buffer_size;
    const int w = std::max(1, int(std::ceil(extent.x / pixel))), h = std::max(1, int(std::ceil(extent.y / pixel)));

    ShaderProgram splat({"particle_footprint.glsl", "harris_splat.vert", "harris_splat.frag"});
    Texture target = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(target.get(), 1, GL_R32F, w, h);
    Framebuffer fbo = make_framebuffer();
    glNamedFramebufferTexture(fbo.get(), GL_COLOR_ATTACHMENT0, target.get(), 0);
    VertexArray vao = make_vertex_array();
    const float one[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    glClearNamedFramebufferfv(fbo.get(), GL_COLOR, 0, one);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.get());
    glViewport(0, 0, w, h);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_DST_COLOR, GL_ZERO);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    splat.set("u_buffer_size", glm::vec2(float(w), float(h)));
    splat.set("u_pixel_m", float(pixel));
    splat.set("u_forward", float(cloud.forward_scattering));
    splat.use();
    glBindVertexArray(vao.get());
    for (std::size_t k : order) {
        const double x = (pu[k] - lo.x) / pixel, y = (pv[k] - lo.y) / pixel;
        // I_k: the buffer at the particle's centre (a read-back: the GPU must finish first).
        float value = 1.0f;
        glReadPixels(std::clamp(int(x), 0, w - 1), std::clamp(int(y), 0, h - 1), 1, 1, GL_RED, GL_FLOAT, &value);
        gamma[k] = value;
        // Its footprint into the buffer.
        const double tau = std::isfinite(P[k].optical_depth) ? P[k].optical_depth : 1e30;
        splat.set("u_particle", glm::vec3(float(x), float(y), float(P[k].radius / pixel)));
        splat.set("u_optics", glm::vec3(float(P[k].radius), float(tau), float(P[k].albedo)));
        glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    }
    glFinish();
    glDisable(GL_BLEND);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (stats)
        *stats = {std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), std::max(w, h),
                  pixel};
    return gamma;
}

}  // namespace kiri::render
