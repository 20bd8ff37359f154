// FroxelPass's passes that fill the volume each update (froxel_pass.hpp): the view's tiles, the
// density, the lighting (a jittered sample, its temporal blend, or a still's samples at once),
// the integration along the slices and the classification of where the apply must march.
#include <algorithm>

#include "froxel_pass_parts.hpp"
#include "kiri/geometry/medium/fog_lighting.hpp"
#include "kiri/geometry/medium/medium.hpp"
#include "sun_volume.hpp"
#include "terrain_pass.hpp"

namespace kiri::render::detail {
namespace {

using namespace froxel_parts;

// A moving view's jitter goes round one Halton cycle, a sample a frame; a still averages the
// cycle's first two samples at once. The volume's J lights the pixels it resolves and the fog in
// front of the layers and the particles; the pixels that march light their own points
// (froxel_march.glsl). Since they do, 4 samples were as close to the CPU reference as the whole
// cycle of 16 (kiri bench --quick --stage views: all 13 views within 0.15 points; agreement and
// frame: the same to 0.01 point; the default view's combined still at 640x360, 4.9 -> 2.4 s), and
// 2 as 4 (all 13 views within 0.02 points, the lake's combined 5.71 -> 5.45 %; the default
// scene's lighting at 1280x720 0.6 -> 0.3 s). Each sample costs one lighting pass.
constexpr int halton_cycle = 16, still_samples = 2;
// froxel_classify.comp: where the volume's lookup may stand for a pixel's own march. The error
// a tap's bilinear lookup may make (in transmittance, or in radiance relative to its tile's
// in-scattering) and how far the fog's edge may spread over a tile's slices. At 0.004 the
// stress tests' anisotropic and far-off slabs drifted up to a point from the reference; at
// 0.002 they stay within 0.1 point of the march everywhere (tests/render/stress_gltest.cpp).
constexpr float classify_tolerance = 0.002f, classify_edge_slices = 1.0f, classify_missed = 0.05f;

double halton(int index, int base)
{
    double f = 1.0, r = 0.0;
    for (; index > 0; index /= base) {
        f /= base;
        r += f * (index % base);
    }
    return r;
}

// One invocation per froxel column (8 x 8 per group) and `depth` in z, then the barrier that
// lets the next pass read what it wrote.
void dispatch_volume(const glm::ivec3& size, int depth)
{
    glDispatchCompute(GLuint((size.x + 7) / 8), GLuint((size.y + 7) / 8), GLuint(depth));
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

}  // namespace

void FroxelPass::run_passes(const FrameContext& frame, GLuint depth_texture, bool still, const FrameSamples* samples)
{
    advance_view(frame);
    run_tiles(frame, depth_texture);
    run_density();
    if (!options_.temporal) {  // one sample at the froxel's centre, the sun steps' middles
        const ScopedPassTimer timed(timers_[lighting]);
        run_lighting(frame, {glm::vec3(0.5f), 0.5f});
    } else if (!still) {  // this frame's sample, blended with the reprojected history
        {
            const ScopedPassTimer timed(timers_[lighting]);
            run_lighting(frame, halton_jitter(frame_index_ % halton_cycle + 1));
        }
        const ScopedPassTimer timed(timers_[temporal]);
        run_temporal(1 - current_, previous_, history_valid_, current_, float(options_.history_weight));
    } else {  // the first samples through the filter at once; the history is the froxel itself
        const ScopedPassTimer timed(timers_[lighting]);
        for (int k = 0; k < still_samples; ++k) {
            // Ping-pong between the two resolved volumes, ending in this frame's.
            const int into = (still_samples - 1 - k) % 2 == 0 ? current_ : 1 - current_;
            run_lighting(frame, halton_jitter(k + 1));
            // The history holds the first k samples: weighted k / (k + 1), the result is their
            // mean.
            run_accumulate(1 - into, k > 0, into, float(k) / float(k + 1));
        }
    }
    if (options_.temporal)
        history_valid_ = true;
    ++frame_index_;
    run_integrate(frame);
    run_classify(frame, depth_texture, samples);
}

FroxelPass::Jitter FroxelPass::halton_jitter(int index)
{
    return {glm::vec3(float(halton(index, 2)), float(halton(index, 3)), float(halton(index, 5))),
            float(halton(index, 7))};
}

void FroxelPass::advance_view(const FrameContext& frame)
{
    const geometry::FroxelOptions& o = options_;
    // This frame's view (the previous one is kept for reprojection).
    previous_ = view_;
    current_ = 1 - current_;
    view_.view_projection = frame.view_projection;
    view_.eye = frame.eye;
    view_.forward = glm::vec3(frame.ray_forward);
    view_.right = glm::vec3(frame.ray_right);
    view_.up = glm::vec3(frame.ray_up);
    const double far_plane = depth_planes(frame).y;
    view_.near = float(o.near);
    view_.far = float(o.far > 0.0 ? o.far : far_plane);
    view_.far = std::max(view_.far, view_.near * 1.01f);
}

void FroxelPass::run_tiles(const FrameContext& frame, GLuint depth_texture)
{
    const geometry::FroxelOptions& o = options_;
    const glm::ivec3 size = v_->size;
    mode_ = FroxelTileBounds::Mode::standard;
    shell_ok_ = false;
    if (o.fog_aware) {
        // The shell's per-pixel depths hold unless the eye is in it (the near plane cuts it).
        shell_ok_ = medium_ &&
            !shell_.contains(glm::dvec3(frame.eye), 2.0 * o.near + 1e-3 * glm::length(glm::dvec3(frame.eye)));
        if (medium_ && !shell_ok_)
            mode_ = FroxelTileBounds::Mode::ground;
        else
            mode_ = o.height_fog.enabled() ? FroxelTileBounds::Mode::haze : FroxelTileBounds::Mode::shell;
    }
    {
        const ScopedPassTimer timed(timers_[shell_stage]);
        use_shell_for_resolution();
        tile_bounds_.rasterise(frame, mode_, shell_ok_);
    }
    const ScopedPassTimer timed(timers_[tiles]);
    // The depths each tile's slices span.
    tile_bounds_.reduce(frame, mode_, {size.x, size.y}, view_.near, view_.far, depth_texture, v_->tiles[current_].get(),
                        o.height_fog.top());
    if (mode_ == FroxelTileBounds::Mode::shell) {  // ranges end where the fog turns opaque
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        bind_layout(opaque_);
        glBindTextureUnit(unit_tiles, 0);  // written below as an image, not read as a texture
        medium_gpu_.bind(opaque_, o.height_fog, unit_medium);
        opaque_.set("u_steps", 48);
        opaque_.use();
        glBindImageTexture(0, v_->tiles[current_].get(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
        glDispatchCompute(GLuint((size.x + 7) / 8), GLuint((size.y + 7) / 8), 1);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
}

void FroxelPass::run_density()
{
    const ScopedPassTimer timed(timers_[density]);
    list_fog_tiles();
    bind_layout(density_);
    medium_gpu_.bind(density_, options_.height_fog, unit_medium);
    density_.set("u_samples", options_.density_samples);
    density_.use();
    // The froxels of the tiles without fog: no fog, and no light (the lighting passes, one or a
    // still's two, write the listed tiles' alone).
    const glm::vec4 no_fog(0.0f), no_light(0.0f, 0.0f, 0.0f, -1.0f);
    glClearTexImage(v_->density.get(), 0, GL_RGBA, GL_FLOAT, &no_fog);
    glClearTexImage(v_->light.get(), 0, GL_RGBA, GL_FLOAT, &no_light);
    glBindImageTexture(0, v_->density.get(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    dispatch_listed(v_->fog_tiles.get());  // the froxels of the tiles with fog
}

void FroxelPass::list_fog_tiles()
{
    const glm::uvec4 groups(0u, GLuint((v_->size.z + 63) / 64), 1u, 0u);
    glNamedBufferSubData(v_->fog_tiles.get(), 0, sizeof groups, &groups);
    bind_layout(fog_tiles_);
    fog_tiles_.use();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, v_->fog_tiles.get());
    glDispatchCompute(GLuint((v_->size.x + 7) / 8), GLuint((v_->size.y + 7) / 8), 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
}

void set_medium_light_uniforms(const ShaderProgram& p, const FrameContext& frame, const geometry::Medium* medium,
                               const geometry::HeightFog& haze, bool fog_shadows)
{
    p.set("u_sun_direction", sun_march_direction(frame.sun_direction));
    p.set("u_sun_radiance", frame.sun_radiance);
    p.set("u_ambient", frame.ambient);
    p.set("u_air", glm::vec4(frame.sky_horizon, frame.haze_density));
    const double albedo = medium ? medium->options().albedo : 0.0, g = medium ? medium->options().anisotropy : 0.0;
    p.set("u_albedo", glm::vec2(float(albedo), float(haze.albedo)));
    p.set("u_anisotropy", glm::vec2(float(g), float(haze.anisotropy)));
    p.set("u_fog_shadows", int(fog_shadows));
    p.set("u_octaves",
          geometry::shader_octaves(geometry::multiple_scattering_of(medium), geometry::scattering_octaves_of(medium)));
}

void FroxelPass::bind_light(const ShaderProgram& p, const FrameContext& frame) const
{
    const geometry::FroxelOptions& o = options_;
    const geometry::HeightFog& haze = o.height_fog;
    // tau_sun: the sun volume's Medium is this one (Renderer::draw), so its grid and uniforms
    // are the same as those bound next.
    if (sun_) {
        sun_->bind(p, unit_sun, o.sun_steps, o.sun_volume);
    } else {
        p.set("u_sv_on", 0);
        p.set("u_sv_steps", o.sun_steps);
        p.set("u_sv_volume", unit_sun + 2);
    }
    medium_gpu_.bind(p, haze, unit_medium);
    bind_terrain_shadow(p, shadow_);
    set_medium_light_uniforms(p, frame, medium_, haze, o.fog_shadows);
    // The baked multiple scattering, with the Medium's model `baked` only (others draw theirs).
    // The Medium's grid is bound already (medium_gpu_ above): the same Medium's.
    if (light_volume_)
        light_volume_->bind(p, unit_light_volume, baked_light(), false);
    else
        LightVolumeTexture{}.bind(p, unit_light_volume, false, false);
    const glm::dvec3 box_lo = medium_ ? medium_->bounds().min : glm::dvec3(0.0);
    const glm::dvec3 box_hi = medium_ ? medium_->bounds().max : glm::dvec3(0.0);
    p.set("u_box_min", glm::vec3(box_lo));
    p.set("u_box_max", glm::vec3(box_hi));
}

void FroxelPass::run_lighting(const FrameContext& frame, const Jitter& jitter)
{
    const ShaderProgram& lighting = program(lighting_);
    bind_layout(lighting);
    bind_light(lighting, frame);
    lighting.set("u_density", unit_density);
    lighting.set("u_jitter", jitter.froxel);
    lighting.set("u_sun_jitter", jitter.sun);
    lighting.set("u_whole_tiles", int(options_.fog_aware));
    lighting.use();
    glBindTextureUnit(unit_density, v_->density.get());
    glBindImageTexture(0, v_->light.get(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    dispatch_listed(v_->fog_tiles.get());  // the froxels of the tiles with fog
}

void FroxelPass::run_accumulate(int history, bool history_valid, int into, float weight)
{
    bind_layout(accumulate_);
    accumulate_.set("u_current", unit_light);
    accumulate_.set("u_history", unit_history);
    accumulate_.set("u_history_valid", int(history_valid));
    accumulate_.set("u_weight", weight);
    accumulate_.use();
    glBindTextureUnit(unit_light, v_->light.get());
    glBindTextureUnit(unit_history, v_->resolved[history].get());
    glBindImageTexture(0, v_->resolved[into].get(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    dispatch_volume(v_->size, v_->size.z);
}

void FroxelPass::run_temporal(int history, const View& from, bool history_valid, int into, float weight)
{
    bind_layout(temporal_);
    temporal_.set("u_current", unit_light);
    temporal_.set("u_history", unit_history);
    temporal_.set("u_history_tiles", unit_history_tiles);
    temporal_.set("u_history_valid", int(history_valid));
    temporal_.set("u_weight", weight);
    temporal_.set("u_previous_view_projection", from.view_projection);
    temporal_.set("u_previous_eye", from.eye);
    temporal_.set("u_previous_forward", from.forward);
    temporal_.use();
    glBindTextureUnit(unit_light, v_->light.get());
    glBindTextureUnit(unit_history, v_->resolved[history].get());
    glBindTextureUnit(unit_history_tiles, v_->tiles[history].get());
    glBindImageTexture(0, v_->resolved[into].get(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    dispatch_volume(v_->size, v_->size.z);
}

void FroxelPass::run_integrate(const FrameContext& frame)
{
    const GLuint lit = options_.temporal ? v_->resolved[current_].get() : v_->light.get();
    const ScopedPassTimer timed(timers_[integrate]);
    const ShaderProgram& p = program(integrate_);
    bind_layout(p);
    bind_light(p, frame);  // the height fog's light
    p.set("u_light", unit_light);
    p.set("u_density", unit_density);
    p.use();
    glBindTextureUnit(unit_light, lit);
    glBindTextureUnit(unit_density, v_->density.get());
    glBindImageTexture(0, v_->integrated.get(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    dispatch_volume(v_->size, 1);
}

void FroxelPass::run_classify(const FrameContext& frame, GLuint depth_texture, const FrameSamples* samples)
{
    // Worth it where most pixels' marches are long: the eye inside the Medium's shell (every
    // ray marches from the eye) or a height fog (every ray marches its haze). Seen from outside
    // without one, the pixels that could read the volume see no fog and already stop at once
    // (on gabilan.bil and Mandakini.bil the same pictures, the classification's cost on top).
    classified_ = options_.fog_aware && (!shell_ok_ || options_.height_fog.enabled());
    if (!classified_)
        return;  // the standard apply reads the volume everywhere; fog-aware, every pixel marches
    const ScopedPassTimer timed(timers_[classify]);
    const ShaderProgram& p = program(classify_);
    classified_ = false;              // the apply's library: every pixel's taps still to be decided
    bind_pixel_program(p, frame, 1);  // the frame's pixels (froxel_frame.glsl), its depth on unit 0
    classified_ = true;
    p.set("u_tolerance", classify_tolerance);
    p.set("u_edge_slices", classify_edge_slices);
    p.use();
    glBindTextureUnit(0, depth_texture);
    glBindImageTexture(0, v_->tiles[current_].get(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    bind_tile_rays();
    glDispatchCompute(GLuint((v_->size.x + 7) / 8), GLuint((v_->size.y + 7) / 8), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                    GL_COMMAND_BARRIER_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
    if (shell_ok_)
        run_tile_rays(frame, depth_texture, samples, classify_missed);
}

}  // namespace kiri::render::detail
