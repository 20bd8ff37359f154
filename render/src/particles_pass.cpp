#include "particles_pass.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "particle_gpu.hpp"

namespace kiri::render::detail {

ParticlesPass::ParticlesPass()
    : program_({"particle_footprint.glsl", "fog_lighting.glsl", "particle_light.glsl", "terrain_shadow.glsl",
                "froxel_fog_none.glsl", "particles.vert", "particles.frag"}),
      composite_({"fullscreen.vert", "particles_composite.frag"}), vao_(make_vertex_array())
{}

bool ParticlesPass::set_particles(const geometry::ParticleCloud& cloud, const ParticleStyle& style)
{
    cloud_ = &cloud;
    style_ = style;
    // The buffer uploads the particles (when they changed); the billboards read the same SSBO.
    buffer_.set_particles(cloud);
    const std::uint64_t hash = hash_particles(cloud);
    if (hash == uploaded_hash_ && count_ == cloud.particles.size() && order_)
        return false;
    count_ = cloud.particles.size();
    order_ = make_buffer();
    if (count_ > 0)
        glNamedBufferStorage(order_.get(), GLsizeiptr(count_ * sizeof(std::uint32_t)), nullptr, GL_DYNAMIC_STORAGE_BIT);
    lo_ = glm::dvec3(1e300);
    hi_ = glm::dvec3(-1e300);
    for (const geometry::Particle& p : cloud.particles) {
        lo_ = glm::min(lo_, p.position - glm::dvec3(p.radius));
        hi_ = glm::max(hi_, p.position + glm::dvec3(p.radius));
    }
    uploaded_hash_ = hash;
    sorted_eye_ = glm::vec3(1e30f);
    return true;
}

void ParticlesPass::clear()
{
    cloud_ = nullptr;
    count_ = 0;
    buffer_.clear();
}

void ParticlesPass::extend_bounds(glm::dvec3& lo, glm::dvec3& hi) const
{
    if (!has_particles())
        return;
    lo = glm::min(lo, lo_);
    hi = glm::max(hi, hi_);
}

void ParticlesPass::ensure_target(int width, int height)
{
    if (width == width_ && height == height_ && fbo_)
        return;
    color_ = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(color_.get(), 1, GL_RGBA16F, width, height);
    fbo_ = make_framebuffer();
    glNamedFramebufferTexture(fbo_.get(), GL_COLOR_ATTACHMENT0, color_.get(), 0);
    width_ = width;
    height_ = height;
}

void ParticlesPass::sort(const FrameContext& frame)
{
    const glm::dmat4 inverse_view = glm::inverse(frame.view);
    const glm::vec3 forward = -glm::vec3(inverse_view[2]);
    if (frame.eye == sorted_eye_ && forward == sorted_forward_)
        return;  // the same view: the order stands
    // Slots of the buffer's particle SSBO (sorted by radius), keyed by depth along the view.
    const std::vector<geometry::Particle>& P = cloud_->particles;
    const std::vector<std::uint32_t>& cloud_index = buffer_.particle_order();
    order_cpu_.resize(cloud_index.size());
    keys_.resize(cloud_index.size());
    const glm::dvec3 eye(frame.eye), f(forward);
    for (std::size_t k = 0; k < cloud_index.size(); ++k)
        keys_[k] = float(glm::dot(P[cloud_index[k]].position - eye, f));
    std::iota(order_cpu_.begin(), order_cpu_.end(), 0u);
    std::sort(order_cpu_.begin(), order_cpu_.end(), [&](std::uint32_t a, std::uint32_t b) {
        return keys_[a] > keys_[b] || (keys_[a] == keys_[b] && a < b);  // far first
    });
    glNamedBufferSubData(order_.get(), 0, GLsizeiptr(order_cpu_.size() * sizeof(std::uint32_t)), order_cpu_.data());
    sorted_eye_ = frame.eye;
    sorted_forward_ = forward;
}

bool ParticlesPass::draw(const FrameContext& frame, unsigned resolved_fbo, unsigned resolved_depth)
{
    if (!has_particles())
        return false;
    const bool rebuilt = buffer_.update(glm::dvec3(frame.sun_direction), style_.buffer);
    light_.update(*cloud_, buffer_, shadow_);
    sort(frame);
    ensure_target(frame.width, frame.height);
    const float clear[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearNamedFramebufferfv(fbo_.get(), GL_COLOR, 0, clear);

    const geometry::LightGrid& g = buffer_.grid();
    const glm::dmat4 inverse_view = glm::inverse(frame.view);
    const double p22 = frame.projection[2][2], p32 = frame.projection[3][2];
    // With froxel fog, the variant that reads it at each billboard's depth (froxel_apply.glsl).
    if (fog_ && !fog_program_)
        fog_program_ = std::make_unique<ShaderProgram>(std::initializer_list<std::string_view>{
            "particle_footprint.glsl", "fog_partition.glsl", "froxel_common.glsl", "fog_lighting.glsl",
            "particle_light.glsl", "terrain_shadow.glsl", "medium_shell.glsl", "froxel_medium.glsl", "froxel_apply.glsl", "particles.vert",
            "particles.frag"});
    const ShaderProgram& p = fog_ ? *fog_program_ : program_;
    if (fog_)
        fog_->bind_apply(p);
    bind_terrain_shadow(p, shadow_);
    set_grid_uniforms(p, g, cloud_->forward_scattering, buffer_.particle_centre());
    p.set("u_centre", glm::vec3(buffer_.particle_centre()));
    p.set("u_view_projection", frame.view_projection);
    p.set("u_camera_right", glm::vec3(inverse_view[0]));
    p.set("u_camera_up", glm::vec3(inverse_view[1]));
    p.set("u_lit", 1);
    p.set("u_self_table", int(light_.has_table()));
    p.set("u_log_gamma", 0);
    p.set("u_depth", 1);
    p.set("u_near", float(p32 / (p22 - 1.0)));
    p.set("u_far", float(p32 / (p22 + 1.0)));
    p.set("u_soft_edge", float(style_.soft_edge));
    p.set("u_anisotropy", float(cloud_->anisotropy));
    p.set("u_eye", frame.eye);
    p.set("u_sun_direction", frame.sun_direction);
    p.set("u_sun_radiance", frame.sun_radiance);
    p.set("u_ambient", frame.ambient);
    p.set("u_sky_horizon", frame.sky_horizon);
    p.set("u_haze_density", frame.haze_density);
    p.set("u_octaves", std::clamp(cloud_->scattering_octaves, 0, 8));
    p.use();
    glBindTextureUnit(0, buffer_.texture());
    glBindTextureUnit(1, resolved_depth);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer_.particle_buffer());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, order_.get());
    light_.bind();
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
    glViewport(0, 0, frame.width, frame.height);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glDisable(GL_CULL_FACE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glBindVertexArray(vao_.get());
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, GLsizei(count_));

    composite_.set("u_particles", 0);
    composite_.use();
    glBindTextureUnit(0, color_.get());
    glBindFramebuffer(GL_FRAMEBUFFER, resolved_fbo);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    return rebuilt;
}

}  // namespace kiri::render::detail
