#include "particles_pass.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "light_volume_texture.hpp"
#include "particle_gpu.hpp"
#include "render_targets.hpp"
#include "shadow_map_pass.hpp"
#include "sun_volume.hpp"

namespace kiri::render::detail {
namespace {
// The baked light's Medium grid and moments, apart from every other sampler of the billboards'
// programs (the froxel apply's among them).
constexpr int unit_baked_moments = 20;  // and 21, 22: the Medium's grid, the cells' floors (LightVolumeTexture::bind)
// The near field's sun volume: the Medium's grid, its noise, the volume (SunVolume::bind).
constexpr int unit_near_sun = 12;  // 12, 13, 14
// The balls' summed density (DensityRatioTexture::bind), and the Medium the ratio divides by it
// (SunVolume::bind: its grid and noise, and the sun volume the balls standing for it are lit by).
constexpr int unit_ratio = 24;
constexpr int unit_ratio_medium = 26;  // 26, 27, 28
// The frame's samples' depth (PARTICLES_AT_SAMPLES); in the composite, their colour.
constexpr int unit_samples_depth = 29;
}  // namespace

ParticlesPass::ParticlesPass()
    : composite_({"fullscreen.vert", "sample_blends.glsl", "particles_composite.frag"}), vao_(make_vertex_array())
{}

bool ParticlesPass::set_particles(const geometry::ParticleCloud& cloud, const ParticleStyle& style)
{
    cloud_ = &cloud;
    if (style.cull_outside_view != style_.cull_outside_view)
        sorted_eye_ = glm::vec3(1e30f);  // what the order holds changes
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
    // The billboards as one indexed draw of two triangles a particle, the vertex shader pulling
    // the particle from the vertex's index (particles.vert), not as one instance each: a software
    // rasteriser pays for every instance (llvmpipe: 20,000 instances of 4 vertices took 3 to 4
    // times as long as one draw of the same vertices).
    std::vector<std::uint32_t> quads(count_ * 6);
    for (std::uint32_t q = 0; q < std::uint32_t(count_); ++q) {
        const std::uint32_t v = 4 * q;
        std::copy_n(std::array<std::uint32_t, 6>{v, v + 1, v + 2, v + 2, v + 1, v + 3}.data(), 6, &quads[6 * q]);
    }
    quad_indices_ = make_buffer();
    if (count_ > 0)
        glNamedBufferStorage(quad_indices_.get(), GLsizeiptr(quads.size() * sizeof(std::uint32_t)), quads.data(), 0);
    glVertexArrayElementBuffer(vao_.get(), quad_indices_.get());
    lo_ = glm::dvec3(1e300);
    hi_ = glm::dvec3(-1e300);
    smallest_radius_ = 1e300;
    largest_radius_ = 0.0;
    for (const geometry::Particle& p : cloud.particles) {
        smallest_radius_ = std::min(smallest_radius_, p.radius);
        largest_radius_ = std::max(largest_radius_, p.radius);
        lo_ = glm::min(lo_, p.position - glm::dvec3(p.radius));
        hi_ = glm::max(hi_, p.position + glm::dvec3(p.radius));
    }
    uploaded_hash_ = hash;
    sorted_eye_ = glm::vec3(1e30f);
    return true;
}

void ParticlesPass::set_resolution(double scale)
{
    std::size_t share = 1;
    if (std::isfinite(scale) && scale > 0.0)
        while (double(2 * share) <= 1.0 / (2.0 * scale) + 1e-9 && share < 64)
            share *= 2;
    if (share != share_)
        sorted_eye_ = glm::vec3(1e30f);  // what the order holds changes
    share_ = share;
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

namespace {

int near_size(int full, int scale) { return std::max(1, (full + scale - 1) / scale); }

// A half-float colour target of w x h, read back bilinearly by the composite.
void make_target(Texture& color, Framebuffer& fbo, int w, int h)
{
    color = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(color.get(), 1, GL_RGBA16F, w, h);
    glTextureParameteri(color.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(color.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(color.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(color.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    fbo = make_framebuffer();
    glNamedFramebufferTexture(fbo.get(), GL_COLOR_ATTACHMENT0, color.get(), 0);
}

}  // namespace

void ParticlesPass::ensure_target(int width, int height, int near_scale, bool at_samples)
{
    if (width == width_ && height == height_ && near_scale == near_scale_ && at_samples == target_samples_ && fbo_)
        return;
    make_target(color_, fbo_, width, height);
    attach_sample_blends(fbo_.get(), sample_colors_, width, height, GL_RGBA16F, at_samples);
    target_samples_ = at_samples;
    if (near_scale > 1) {
        make_target(near_color_, near_fbo_, near_size(width, near_scale), near_size(height, near_scale));
        make_target(around_color_, around_fbo_, near_size(width, 2 * near_scale), near_size(height, 2 * near_scale));
    }
    width_ = width;
    height_ = height;
    near_scale_ = near_scale;
}

std::size_t ParticlesPass::near_first(const FrameContext& frame) const
{
    if (style_.near_scale <= 1 || !(style_.near_pixels > 0.0))
        return order_cpu_.size();
    // A billboard of radius r at depth d along the view spans r P / d pixels (P: pixels per unit
    // of tan, the projection's y scale times half the height): every one nearer than
    // r_min P / near_pixels spans near_pixels or more. The order is far to near.
    const double pixels_per_tan = frame.projection[1][1] * 0.5 * frame.height;
    const float nearer = float(smallest_radius_ * std::sqrt(double(share_)) * pixels_per_tan / style_.near_pixels);
    const auto first =
        std::partition_point(order_cpu_.begin(), order_cpu_.end(), [&](std::uint32_t k) { return keys_[k] >= nearer; });
    return std::size_t(first - order_cpu_.begin());
}

std::size_t ParticlesPass::around_first() const
{
    // Every ball that can hold the eye: its centre within the largest radius of it. The order is
    // far to near by depth, which is no more than the distance. (Within 1.5 radii, where
    // particles.vert begins to draw a billboard over the whole screen, took more of the near
    // billboards for nearly the same picture inside the descent's fog: 4.07 against 4.17 % off
    // the baked reference, both in the near target.)
    const float within = float(largest_radius_ * std::sqrt(double(share_)));
    const auto first =
        std::partition_point(order_cpu_.begin(), order_cpu_.end(), [&](std::uint32_t k) { return keys_[k] >= within; });
    return std::size_t(first - order_cpu_.begin());
}

void ParticlesPass::update_baked_lights(const FrameContext& frame)
{
    if (baked_sort_ == sorts_ && baked_volume_updates_ == light_volume_->updates())
        return;  // the same billboards, eye and volume
    if (!baked_program_)
        baked_program_ = std::make_unique<ShaderProgram>(std::initializer_list<std::string_view>{
            "particle_footprint.glsl", "medium_shell.glsl", "light_volume.glsl", "particle_baked.comp"});
    const std::size_t slots = buffer_.particle_order().size();
    if (slots > baked_capacity_ || !baked_lights_) {
        baked_lights_ = make_buffer();
        glNamedBufferStorage(baked_lights_.get(), GLsizeiptr(std::max<std::size_t>(slots, 1) * 4 * sizeof(float)),
                             nullptr, 0);
        baked_capacity_ = slots;
    }
    const ShaderProgram& p = *baked_program_;
    light_volume_->bind(p, unit_baked_moments, true);
    p.set("u_count", int(order_cpu_.size()));
    p.set("u_eye", frame.eye);
    p.set("u_centre", glm::vec3(buffer_.particle_centre()));
    p.set("u_anisotropy", float(cloud_->anisotropy));
    p.use();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer_.particle_buffer());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, order_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, baked_lights_.get());
    glDispatchCompute(GLuint((order_cpu_.size() + 63) / 64), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    baked_sort_ = sorts_;
    baked_volume_updates_ = light_volume_->updates();
}

double ParticlesPass::near_field_reach(const FrameContext& frame) const
{
    // Under froxel fog the froxels draw the fog near the eye (combined mode); the march needs the
    // Medium and its sun volume, and particles that carry its optics (a "particles" section with
    // its own extinction or albedo draws a fog the Medium is not).
    if (fog_ || !sun_ || !sun_->ready() || !sun_->medium() || !(style_.near_field > 0.0) || style_.near_field_steps < 1)
        return 0.0;
    const geometry::MediumOptions& optics = sun_->medium()->options();
    if (cloud_->extinction != optics.extinction || cloud_->albedo != optics.albedo)
        return 0.0;
    const double reach = style_.near_field * largest_radius_ * std::sqrt(double(share_));
    // Only where a ball can reach within it of the eye: the eye within `reach` of the box that
    // holds every ball.
    const glm::dvec3 eye(frame.eye);
    const glm::dvec3 outside = glm::max(glm::max(lo_ - eye, eye - hi_), glm::dvec3(0.0));
    return glm::length(outside) < reach ? reach : 0.0;
}

void ParticlesPass::draw_near_field(const FrameContext& frame, double reach, bool baked, unsigned resolved_fbo,
                                    unsigned resolved_depth)
{
    // At the near billboards' resolution (smooth at that scale as they are: the fog within a few
    // hundred metres of the eye), then laid over the frame like them; keeping 320 x 180 texels at
    // least, as the layers' reduced target does (on a small frame a coarser one blurs the ground's
    // silhouettes within the reach over a wide angle: the canyon from inside its fog at 160 x 90
    // 1.67 % off the reference at full resolution, 2.79 % at half).
    int scale = std::max(near_scale_, 1);
    while (scale > 1 && (frame.width / scale < 320 || frame.height / scale < 180))
        --scale;
    const int w = near_size(frame.width, scale), h = near_size(frame.height, scale);
    std::unique_ptr<ShaderProgram>& slot = near_programs_[baked ? 1 : 0];
    if (!slot)
        slot = std::make_unique<ShaderProgram>(
            std::vector<std::string_view>{
                "fullscreen.vert", "view_depth.glsl", "fog_partition.glsl", "froxel_common.glsl", "fog_lighting.glsl",
                "medium_shell.glsl", "height_fog.glsl", "froxel_medium.glsl", "sun_march.glsl", "sun_volume.glsl",
                "terrain_shadow.glsl", "light_volume.glsl", "froxel_light.glsl", "particles_near.frag"},
            std::string(light_volume_preamble(baked)));
    const ShaderProgram& p = *slot;
    // The Medium as the sun volume holds it (its grid and noise too), without the height fog:
    // the particles draw the Medium alone, and light it through the Medium alone.
    sun_->bind(p, unit_near_sun, 64, true);
    FroxelMedium::bind_height_fog(p, geometry::HeightFog{});
    if (light_volume_)
        light_volume_->bind(p, unit_baked_moments, baked, false);
    else
        LightVolumeTexture{}.bind(p, unit_baked_moments, false, false);
    bind_terrain_shadow(p, shadow_);
    p.set("u_partitioned", 0);
    p.set("u_fx_eye", frame.eye);
    p.set("u_fx_forward", glm::vec3(frame.ray_forward));
    p.set("u_fx_right", glm::vec3(frame.ray_right));
    p.set("u_fx_up", glm::vec3(frame.ray_up));
    set_medium_light_uniforms(p, frame, sun_->medium(), geometry::HeightFog{}, true);
    const glm::vec2 planes = depth_planes(frame);
    p.set("u_near", planes.x);
    p.set("u_far", planes.y);
    p.set("u_depth", 1);
    p.set("u_depth_scale", glm::vec2(float(frame.width) / float(w), float(frame.height) / float(h)));
    p.set("u_reach", float(reach));
    p.set("u_steps", style_.near_field_steps);
    p.use();
    glBindTextureUnit(1, resolved_depth);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    if (scale > 1) {
        if (near_field_size_ != glm::ivec2(w, h) || !near_field_fbo_) {
            make_target(near_field_color_, near_field_fbo_, w, h);
            near_field_size_ = glm::ivec2(w, h);
        }
        const float clear[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        glClearNamedFramebufferfv(near_field_fbo_.get(), GL_COLOR, 0, clear);
        glBindFramebuffer(GL_FRAMEBUFFER, near_field_fbo_.get());
    } else {
        glBindFramebuffer(GL_FRAMEBUFFER, resolved_fbo);
    }
    glViewport(0, 0, w, h);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    if (scale > 1) {
        composite_.use();
        composite_.set("u_particles", 0);
        composite_.set("u_inv_size", glm::vec2(1.0f / float(frame.width), 1.0f / float(frame.height)));
        glBindFramebuffer(GL_FRAMEBUFFER, resolved_fbo);
        glViewport(0, 0, frame.width, frame.height);
        glBindTextureUnit(0, near_field_color_.get());
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
}

std::uint64_t ParticlesPass::last_fragments() const
{
    if (fragments_pending_) {
        GLuint64 fragments = 0;
        glGetQueryObjectui64v(fragments_query_.get(), GL_QUERY_RESULT, &fragments);
        last_fragments_ = fragments;
        fragments_pending_ = false;
    }
    return last_fragments_;
}

void ParticlesPass::sort(const FrameContext& frame)
{
    const glm::dmat4 inverse_view = glm::inverse(frame.view);
    const glm::vec3 forward = -glm::vec3(inverse_view[2]);
    if (frame.eye == sorted_eye_ && forward == sorted_forward_ && frame.projection == sorted_projection_)
        return;  // the same view: the order stands
    // A particle's footprint lies within its radius of its centre: one wholly outside a side of
    // the view's pyramid, or behind the eye, reaches no pixel and is not drawn (a software
    // rasteriser shades every billboard's vertices on one thread, whether it is seen or not).
    // The sides' distances in view space: (|x| - depth tan) cos, with the tan of half the view's
    // angle across and up.
    const double tan_x = 1.0 / frame.projection[0][0], tan_y = 1.0 / frame.projection[1][1];
    const double cos_x = 1.0 / std::sqrt(1.0 + tan_x * tan_x), cos_y = 1.0 / std::sqrt(1.0 + tan_y * tan_y);
    const std::vector<geometry::Particle>& P = cloud_->particles;
    const std::vector<std::uint32_t>& cloud_index = buffer_.particle_order();  // slots of the particle SSBO
    order_cpu_.clear();
    keys_.resize(cloud_index.size());
    // Every share_-th slot: the slots run by radius, so the share keeps the cloud's mix of sizes.
    for (std::size_t k = 0; k < cloud_index.size(); ++k) {
        if (k % share_ != 0)
            continue;
        const geometry::Particle& p = P[cloud_index[k]];
        const double radius = p.radius * std::sqrt(double(share_));
        const glm::dvec3 v(frame.view * glm::dvec4(p.position, 1.0));
        const double depth = -v.z;
        keys_[k] = float(depth);
        if (style_.cull_outside_view &&
            (depth < -radius || (std::abs(v.x) - depth * tan_x) * cos_x > radius ||
             (std::abs(v.y) - depth * tan_y) * cos_y > radius))
            continue;
        order_cpu_.push_back(std::uint32_t(k));
    }
    std::sort(order_cpu_.begin(), order_cpu_.end(), [&](std::uint32_t a, std::uint32_t b) {
        return keys_[a] > keys_[b] || (keys_[a] == keys_[b] && a < b);  // far first
    });
    if (!order_cpu_.empty())
        glNamedBufferSubData(order_.get(), 0, GLsizeiptr(order_cpu_.size() * sizeof(std::uint32_t)), order_cpu_.data());
    ++sorts_;
    sorted_eye_ = frame.eye;
    sorted_forward_ = forward;
    sorted_projection_ = frame.projection;
}

bool ParticlesPass::at_samples(const FrameContext& frame, const FrameSamples* samples) const
{
    return samples != nullptr && samples->depth != 0 && samples->offsets != nullptr && samples->count == 4 &&
        frame.still && !fog_ && frame.width * frame.height <= max_pixels_at_samples;
}

bool ParticlesPass::draw(const FrameContext& frame, unsigned resolved_fbo, unsigned resolved_depth,
                         const FrameSamples* samples)
{
    if (!has_particles())
        return false;
    const bool rebuilt = buffer_.update(glm::dvec3(frame.sun_direction), style_.buffer);
    last_light_rebuilt_ = light_.update(*cloud_, buffer_, shadow_, sun_);
    sort(frame);
    // The particles alone, standing for the Medium, draw it (density_ratio.hpp); under froxel fog
    // they draw their share of it, and the ratio is not written for a share.
    const geometry::Medium* matched = style_.match_medium && !fog_ && sun_ ? sun_->medium() : nullptr;
    ratio_.update(*cloud_, uploaded_hash_, matched, buffer_.particle_centre());
    const bool ratio = matched && ratio_.ready();
    const bool sampled = ratio && at_samples(frame, samples);
    const int scale = std::max(style_.near_scale, 1);
    ensure_target(frame.width, frame.height, scale, sampled);
    const std::size_t drawn = order_cpu_.size(), split = near_first(frame), around = around_first();
    // The baked multiple scattering (particle_baked.comp, particles.frag): the moments and the
    // Medium's columns they follow. The renderer gives a volume for the model `baked` alone.
    const bool baked = light_volume_ && light_volume_->ready();
    const float clear[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (int b = 0; b < (sampled ? 4 : 1); ++b)
        glClearNamedFramebufferfv(fbo_.get(), GL_COLOR, b, clear);
    if (split < drawn)
        glClearNamedFramebufferfv(near_fbo_.get(), GL_COLOR, 0, clear);
    // With the baked light the billboards around the eye read it at each fragment, in a target of
    // their own (else they are drawn with the near ones).
    const bool around_coarse = baked && scale > 1 && around < drawn;
    if (around_coarse)
        glClearNamedFramebufferfv(around_fbo_.get(), GL_COLOR, 0, clear);

    const geometry::LightGrid& g = buffer_.grid();
    const glm::dmat4 inverse_view = glm::inverse(frame.view);
    const glm::vec2 planes = depth_planes(frame);
    // With froxel fog, the variant that reads it at each billboard's depth (froxel_apply.glsl).
    // With the gain table (nearly always), the variant that reads it alone.
    const bool table = light_.has_table();
    if (baked)
        update_baked_lights(frame);
    const double near_reach = near_field_reach(frame);
    const auto program = [&](bool per_fragment, bool sample_rays) -> const ShaderProgram& {
        std::unique_ptr<ShaderProgram>& slot = programs_[fog_ ? 1 : 0][baked ? 1 + int(per_fragment) : 0][table ? 1 : 0]
                                                        [ratio ? 1 : 0][sample_rays ? 1 : 0];
        if (!slot)
            slot = std::make_unique<ShaderProgram>(
                fog_ ? std::vector<std::string_view>{"view_depth.glsl", "particle_footprint.glsl", "fog_partition.glsl",
                                                     "froxel_common.glsl", "fog_lighting.glsl", "particle_light.glsl",
                                                     "terrain_shadow.glsl", "medium_shell.glsl", "height_fog.glsl",
                                                     "froxel_medium.glsl", "froxel_apply.glsl", "light_volume.glsl",
                                                     "particles.vert", "particles.frag"}
                     : std::vector<std::string_view>{"view_depth.glsl", "depth_samples.glsl", "particle_footprint.glsl",
                                                     "fog_partition.glsl", "froxel_common.glsl", "fog_lighting.glsl",
                                                     "particle_light.glsl", "terrain_shadow.glsl",
                                                     "froxel_fog_none.glsl", "medium_shell.glsl", "height_fog.glsl",
                                                     "froxel_medium.glsl", "sun_march.glsl", "sun_volume.glsl",
                                                     "light_volume.glsl", "particles.vert", "particles.frag"},
                std::string(light_volume_preamble(baked)) + (table ? "#define KIRI_SELF_TABLE\n" : "") +
                    (baked && per_fragment ? "#define KIRI_BAKED_PER_FRAGMENT\n" : "") +
                    (ratio ? "#define KIRI_DENSITY_RATIO\n" : "") +
                    (sample_rays ? "#define PARTICLES_AT_SAMPLES\n" : ""));
        return *slot;
    };
    // Each program drawn with takes the frame's uniforms and bindings.
    const auto prepare = [&](const ShaderProgram& p) {
        if (fog_)
            fog_->bind_apply(p);
        bind_terrain_shadow(p, shadow_);
        // The volume's own copy of the Medium's grid, after bind_apply: the froxels bind theirs only
        // where they apply fog, and their apply's lookups in these programs do not read it.
        if (light_volume_)
            light_volume_->bind(p, unit_baked_moments, baked);
        else
            LightVolumeTexture{}.bind(p, unit_baked_moments, false);
        set_grid_uniforms(p, g, cloud_->forward_scattering, buffer_.particle_centre());
        if (sampled) {
            p.set("u_samples_depth", unit_samples_depth);
            p.set("u_samples", samples->count);
            glProgramUniform2fv(p.id(), p.location("u_offsets"), 8, samples->offsets);
            glBindTextureUnit(unit_samples_depth, samples->depth);
        }
        p.set("u_centre", glm::vec3(buffer_.particle_centre()));
        {
            const glm::dvec2 c(buffer_.particle_centre());
            const auto bound = [](double v) { return float(std::clamp(v, -1e30, 1e30)); };
            const glm::dvec2 lo = cloud_->fog_xy_min - c, hi = cloud_->fog_xy_max - c;
            p.set("u_fog_xy", glm::vec4(bound(lo.x), bound(lo.y), bound(hi.x), bound(hi.y)));
        }
        p.set("u_view_projection", frame.view_projection);
        p.set("u_camera_right", glm::vec3(inverse_view[0]));
        p.set("u_camera_up", glm::vec3(inverse_view[1]));
        p.set("u_camera_forward", -glm::vec3(inverse_view[2]));
        p.set("u_tan_half", glm::vec2(1.0 / frame.projection[0][0], 1.0 / frame.projection[1][1]));
        p.set("u_lit", 1);
        p.set("u_self_table", int(light_.has_table()));
        p.set("u_log_gamma", 0);
        p.set("u_depth", 1);
        p.set("u_near", planes.x);
        p.set("u_far", planes.y);
        p.set("u_soft_edge", float(style_.soft_edge));
        p.set("u_anisotropy", float(cloud_->anisotropy));
        set_light_uniforms(p, frame);
        p.set("u_octaves", std::clamp(cloud_->scattering_octaves, 0, 8));
        p.set("u_radius_scale", float(std::sqrt(double(share_))));
        p.set("u_near_field", float(near_reach));
        ratio_.bind(p, unit_ratio);
        if (!fog_) {
            // The Medium the ratio reads (froxel_medium.glsl) and its optical depth towards the sun
            // (sun_volume.glsl), its samplers on units of their own either way: samplers of
            // different types may not share a unit, used or not.
            if (ratio) {
                sun_->bind(p, unit_ratio_medium, 48, true);
                p.set("u_sv_direction", sun_march_direction(frame.sun_direction));
            } else {
                p.set("u_md_on", 0);
                p.set("u_sv_on", 0);
                p.set("u_sv_volume", unit_ratio_medium + 2);
                p.set("u_md_grid", unit_ratio_medium);
                p.set("u_md_noise", unit_ratio_medium + 1);
            }
        }
        p.use();
        glBindTextureUnit(0, buffer_.texture());
        glBindTextureUnit(1, resolved_depth);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer_.particle_buffer());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, order_.get());
        light_.bind();
        if (baked)
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, baked_lights_.get());
    };
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glDisable(GL_CULL_FACE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glBindVertexArray(vao_.get());
    if (!fragments_query_)
        fragments_query_ = make_query(GL_SAMPLES_PASSED);
    glBeginQuery(GL_SAMPLES_PASSED, fragments_query_.get());
    const auto draw_range = [&](const ShaderProgram& p, std::size_t first, std::size_t n, unsigned fbo, int w, int h) {
        if (n == 0)
            return;
        glProgramUniform1ui(p.id(), p.location("u_first"), GLuint(first));
        p.set("u_depth_scale", glm::vec2(float(frame.width) / float(w), float(frame.height) / float(h)));
        p.set("u_pixel_angle", float(2.0 / (frame.projection[1][1] * double(h))));
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glViewport(0, 0, w, h);
        glDrawElements(GL_TRIANGLES, GLsizei(6 * n), GL_UNSIGNED_INT, nullptr);
    };
    // Far to near: those beyond the split at full resolution, the near ones in the coarse target,
    // those around the eye last (with the baked light, in the program that reads it per fragment).
    const int near_w = near_size(frame.width, scale), near_h = near_size(frame.height, scale);
    const std::size_t far_end = std::min(split, around);
    // At the samples (a small still): the billboards drawn at the frame's resolution along each
    // sample's ray; the coarser targets' at their pixels' centres.
    const ShaderProgram& per_particle = program(false, false);
    const ShaderProgram& per_particle_full = sampled ? program(false, true) : per_particle;
    prepare(per_particle_full);
    draw_range(per_particle_full, 0, far_end, fbo_.get(), frame.width, frame.height);
    if (around > far_end) {
        if (&per_particle != &per_particle_full)
            prepare(per_particle);
        draw_range(per_particle, far_end, around - far_end, near_fbo_.get(), near_w, near_h);
    }
    if (around < drawn) {
        const bool full = !around_coarse && split >= drawn;
        const ShaderProgram& per_fragment = program(true, full && sampled);
        prepare(per_fragment);
        if (around_coarse)
            draw_range(per_fragment, around, drawn - around, around_fbo_.get(), near_size(frame.width, 2 * scale),
                       near_size(frame.height, 2 * scale));
        else if (split < drawn)
            draw_range(per_fragment, around, drawn - around, near_fbo_.get(), near_w, near_h);
        else
            draw_range(per_fragment, around, drawn - around, fbo_.get(), frame.width, frame.height);
    }
    glEndQuery(GL_SAMPLES_PASSED);
    fragments_pending_ = true;
    last_near_ = int(drawn - split);

    // Premultiplied "over" is associative: the near billboards' layer over the far ones' equals
    // every billboard blended over the frame in one order.
    composite_.set("u_particles", 0);
    composite_.set("u_sample1", 1);
    composite_.set("u_sample2", 2);
    composite_.set("u_sample3", 3);
    composite_.set("u_samples_color", 4);
    composite_.use();
    glBindFramebuffer(GL_FRAMEBUFFER, resolved_fbo);
    glViewport(0, 0, frame.width, frame.height);
    composite_.set("u_inv_size", glm::vec2(0.0f));
    composite_.set("u_at_samples", int(sampled));
    composite_.set("u_samples_below", int(sampled && samples->color != 0));
    glBindTextureUnit(0, color_.get());
    if (sampled) {
        for (int b = 0; b < 3; ++b)
            glBindTextureUnit(GLuint(1 + b), sample_colors_[b].get());
        glBindTextureUnit(4, samples->color);
    }
    glDrawArrays(GL_TRIANGLES, 0, 3);
    composite_.set("u_at_samples", 0);
    composite_.set("u_inv_size", glm::vec2(1.0f / float(frame.width), 1.0f / float(frame.height)));
    if (split < drawn) {
        glBindTextureUnit(0, near_color_.get());
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    if (around_coarse) {
        glBindTextureUnit(0, around_color_.get());
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    // The near field lies in front of every billboard: over all of them.
    if (near_reach > 0.0)
        draw_near_field(frame, near_reach, baked, resolved_fbo, resolved_depth);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    return rebuilt;
}

}  // namespace kiri::render::detail
