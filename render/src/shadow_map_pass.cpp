#include "shadow_map_pass.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "probe_readback.hpp"
#include "terrain_pass.hpp"

namespace kiri::render::detail {
namespace {

constexpr int blur_radius = 2;  // texels each side: a 5-tap Gaussian per axis

void nearest_clamped(GLuint texture, GLint filter)
{
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, filter);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, filter);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

}  // namespace

ShadowMapPass::ShadowMapPass() : depth_program_({"terrain.vert", "depth_only.frag"}), blur_({"esm_blur.comp"}) {}

bool ShadowMapPass::update(const TerrainPass& terrain, const glm::vec3& sun, const glm::dvec3& lo, const glm::dvec3& hi,
                           int size, double sharpness)
{
    if (!terrain.has_terrain())
        return false;
    // A ray towards a sun below the horizon descends for ever: it meets the surround, flat at its
    // base level out to the horizon, whatever height it starts from (at the grid's edge the
    // surround is continuous with it). So the sun sets for the whole fog at once.
    sun_set_ = sun.z < 0.0f && terrain.surround();
    if (ready() && sun == sun_ && lo == lo_ && hi == hi_ && size == size_ && sharpness == sharpness_ &&
        terrain_ == terrain.identity())
        return false;
    // Light frame: looking down the sun's rays; the region's corners bound it.
    const glm::dvec3 s = glm::normalize(glm::dvec3(sun));
    const glm::dvec3 helper = std::abs(s.z) < 0.9 ? glm::dvec3(0.0, 0.0, 1.0) : glm::dvec3(1.0, 0.0, 0.0);
    const glm::dvec3 centre = 0.5 * (lo + hi);
    const double radius = 0.5 * glm::length(hi - lo) + 1.0;
    const glm::dmat4 view = glm::lookAt(centre + s * (radius * 2.0), centre, helper);
    glm::dvec3 a(1e300), b(-1e300);
    for (int c = 0; c < 8; ++c) {
        const glm::dvec3 corner(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z);
        const glm::dvec3 v(view * glm::dvec4(corner, 1.0));
        a = glm::min(a, v);
        b = glm::max(b, v);
    }
    const double margin = 1e-3 * radius;
    const glm::dmat4 projection =
        glm::ortho(a.x - margin, b.x + margin, a.y - margin, b.y + margin, -b.z - margin, -a.z + margin);
    const double depth_range = (b.z - a.z) + 2.0 * margin;
    const glm::dmat4 to_unit = glm::translate(glm::dmat4(1.0), glm::dvec3(0.5, 0.5, 0.5 * depth_range)) *
        glm::scale(glm::dmat4(1.0), glm::dvec3(0.5, 0.5, 0.5 * depth_range));
    matrix_ = glm::mat4(to_unit * projection * view);
    texel_m_ = float(std::max(b.x - a.x, b.y - a.y) / size);
    depth_range_ = float(depth_range);
    k_ = float(sharpness / std::max(double(texel_m_), 1e-9));

    if (size != size_ || !fbo_) {
        depth_ = make_texture(GL_TEXTURE_2D);
        glTextureStorage2D(depth_.get(), 1, GL_DEPTH_COMPONENT32F, size, size);
        nearest_clamped(depth_.get(), GL_NEAREST);
        for (Texture& t : esm_) {
            t = make_texture(GL_TEXTURE_2D);
            glTextureStorage2D(t.get(), 1, GL_R32F, size, size);
            nearest_clamped(t.get(), GL_LINEAR);
        }
        fbo_ = make_framebuffer();
        glNamedFramebufferTexture(fbo_.get(), GL_DEPTH_ATTACHMENT, depth_.get(), 0);
        glNamedFramebufferDrawBuffer(fbo_.get(), GL_NONE);
        size_ = size;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
    glViewport(0, 0, size, size);
    const float far_depth = 1.0f;
    glClearNamedFramebufferfv(fbo_.get(), GL_DEPTH, 0, &far_depth);
    depth_program_.set("u_view_projection", glm::mat4(projection * view));
    depth_program_.use();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    terrain.draw_mesh();

    blur_.set("u_size", glm::ivec2(size));
    blur_.set("u_k_metres", float(k_ * depth_range));
    blur_.set("u_radius", blur_radius);
    blur_.set("u_source", 0);
    blur_.use();
    const GLuint groups = GLuint((size + 7) / 8);
    for (int pass = 0; pass < 2; ++pass) {
        blur_.set("u_pass", pass);
        glBindTextureUnit(0, pass == 0 ? depth_.get() : esm_[0].get());
        glBindImageTexture(0, esm_[pass].get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
        glDispatchCompute(groups, groups, 1);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
    sun_ = sun;
    lo_ = lo;
    hi_ = hi;
    sharpness_ = sharpness;
    terrain_ = terrain.identity();
    ++updates_;
    return true;
}

void ShadowMapPass::bind(const ShaderProgram& program, bool on) const
{
    program.set("u_ts_on", int(on && ready()));
    program.set("u_ts_esm", shadow_map_unit);  // even when off: its unit must not be another type's
    program.set("u_ts_raw", shadow_depth_unit);
    if (!on || !ready())
        return;
    program.set("u_ts_sun_set", int(sun_set_));
    program.set("u_ts_matrix", matrix_);
    program.set("u_ts_k", k_);
    program.set("u_ts_bias", texel_m_);
    program.set("u_ts_depth", depth_range_);
    glBindTextureUnit(GLuint(shadow_map_unit), esm_[1].get());
    glBindTextureUnit(GLuint(shadow_depth_unit), depth_.get());
}

void bind_terrain_shadow(const ShaderProgram& program, const ShadowMapPass* map)
{
    if (map) {
        map->bind(program, true);
        return;
    }
    program.set("u_ts_on", 0);
    program.set("u_ts_esm", shadow_map_unit);
    program.set("u_ts_raw", shadow_depth_unit);
}

std::vector<float> ShadowMapPass::probe(const std::vector<glm::vec3>& points) const
{
    if (points.empty())
        return {};
    if (!probe_)
        probe_ = std::make_unique<ShaderProgram>(
            std::initializer_list<std::string_view>{"terrain_shadow.glsl", "terrain_shadow_probe.comp"});
    std::vector<glm::vec4> in(points.size());
    for (std::size_t k = 0; k < points.size(); ++k)
        in[k] = glm::vec4(points[k], 1.0f);
    bind(*probe_, true);
    return run_point_probe(*probe_, in.data(), in.size() * sizeof(glm::vec4), in.size());
}

}  // namespace kiri::render::detail
