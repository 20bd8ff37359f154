#include "froxel_pass.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>

#include "kiri/geometry/medium/fog_lighting.hpp"
#include "kiri/geometry/medium/medium.hpp"
#include "sun_volume.hpp"
#include "terrain_pass.hpp"

namespace kiri::render::detail {
namespace {

// Texture units: the apply's (8..10) stay clear of the terrain's and layers' (0..2).
// Unit 10 is the sun's shadow map's (shadow_map_unit).
constexpr int unit_tiles = 8, unit_volume = 9, unit_medium = 11;  // 11, 12
constexpr int unit_density = 13, unit_light = 14, unit_history = 15, unit_history_tiles = 7;
constexpr int unit_shell_depths = 5;
constexpr int unit_sun = 16;           // 16, 17, 18
constexpr int unit_light_volume = 19;  // and 21: the cells' floors (LightVolumeTexture::bind)
// A moving view's jitter goes round one Halton cycle, a sample a frame; a still averages the
// cycle's first two samples at once. The volume's J lights the pixels it resolves and the fog in
// front of the layers and the particles; the pixels that march light their own points
// (froxel_march.glsl). Since they do, 4 samples were as close to the CPU reference as the whole
// cycle of 16 (kiri bench --quick --stage views: all 13 views within 0.15 points; agreement and
// frame: the same to 0.01 point; the default view's combined still at 640x360, 4.9 -> 2.4 s), and
// 2 as 4 (all 13 views within 0.02 points, the lake's combined 5.71 -> 5.45 %; the default
// scene's lighting at 1280x720 0.6 -> 0.3 s). Each sample costs one lighting pass.
constexpr int halton_cycle = 16, still_samples = 2;
// The apply's work in three timers (a GL timer query cannot nest): the grids and the marches of
// the pixels the volume does not resolve, the split pixels' samples' marches, the frame's fog.
// The shell's rasterisation is timed apart from the tiles' reduction: a raster pass and a
// compute pass, which a data-centre GPU runs at very different speeds (docs/speed.md).
enum Stage {
    shell_stage,
    tiles,
    density,
    lighting,
    temporal,
    integrate,
    classify,
    marches,
    splits,
    apply_stage,
    stage_count
};
const char* const stage_names[stage_count] = {
    "froxel shell",     "froxel tiles",    "froxel density", "froxel lighting", "froxel temporal",
    "froxel integrate", "froxel classify", "froxel marches", "froxel splits",   "froxel apply"};
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

Texture make_volume(const glm::ivec3& size, GLenum format)
{
    Texture t = make_texture(GL_TEXTURE_3D);
    glTextureStorage3D(t.get(), 1, format, size.x, size.y, size.z);
    glTextureParameteri(t.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
}

Texture make_tiles(const glm::ivec2& size)
{
    Texture t = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(t.get(), 1, GL_RGBA32F, size.x, size.y);
    glTextureParameteri(t.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
}

// One invocation per froxel column (8 x 8 per group) and `depth` in z, then the barrier that
// lets the next pass read what it wrote.
void dispatch_volume(const glm::ivec3& size, int depth)
{
    glDispatchCompute(GLuint((size.x + 7) / 8), GLuint((size.y + 7) / 8), GLuint(depth));
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

// The libraries of a program that lights fog (froxel_light.glsl), then its stage file.
std::vector<std::string_view> light_libraries(std::string_view stage)
{
    return {"fog_partition.glsl",  "froxel_common.glsl", "fog_lighting.glsl", "medium_shell.glsl",
            "height_fog.glsl",     "froxel_medium.glsl", "sun_march.glsl",    "sun_volume.glsl",
            "terrain_shadow.glsl", "light_volume.glsl",  "froxel_light.glsl", stage};
}

// The libraries of a program that marches pixels' rays (froxel_march.glsl), then its stage file.
std::vector<std::string_view> march_libraries(std::string_view stage)
{
    std::vector<std::string_view> files = light_libraries("froxel_apply.glsl");
    files.insert(files.end(), {"froxel_march.glsl", stage});
    return files;
}

// Those of a program over the frame's pixels (froxel_frame.glsl) that marches their rays.
std::vector<std::string_view> pixel_libraries(std::string_view stage)
{
    std::vector<std::string_view> files = march_libraries("froxel_frame.glsl");
    files.insert(files.end(), {"froxel_grid_point.glsl", stage});
    return files;
}

// Those of the pass that finds the pixels whose samples see different fog (froxel_edges.comp).
std::vector<std::string_view> edge_libraries()
{
    std::vector<std::string_view> files = pixel_libraries("depth_samples.glsl");
    files.push_back("froxel_edges.comp");
    return files;
}

}  // namespace

struct FroxelPass::Volumes {
    glm::ivec3 size{0};
    Texture density, light, resolved[2], integrated, tiles[2];
};

FroxelPass::FroxelPass()
    : v_(std::make_unique<Volumes>()),
      density_({"fog_partition.glsl", "froxel_common.glsl", "fog_lighting.glsl", "medium_shell.glsl", "height_fog.glsl",
                "froxel_medium.glsl", "froxel_density.comp"}),
      lighting_(light_libraries("froxel_lighting.comp")), temporal_({"froxel_common.glsl", "froxel_temporal.comp"}),
      accumulate_({"froxel_common.glsl", "froxel_accumulate.comp"}),
      opaque_({"fog_partition.glsl", "froxel_common.glsl", "fog_lighting.glsl", "medium_shell.glsl", "height_fog.glsl",
               "froxel_medium.glsl", "froxel_opaque.comp"}),
      integrate_(light_libraries("froxel_integrate.comp")), classify_(march_libraries("froxel_classify.comp")),
      pixels_(pixel_libraries("froxel_pixels.comp")), upsample_(pixel_libraries("froxel_upsample.comp")),
      apply_program_({"froxel_apply.comp"}), readback_({"froxel_frame.glsl", "froxel_readback.comp"}),
      edges_(edge_libraries())
{
    for (const char* name : stage_names)
        timers_.emplace_back(name);
}

const ShaderProgram& FroxelPass::HazeVariants::get(bool height_fog)
{
    std::unique_ptr<ShaderProgram>& p = programs_[height_fog ? 1 : 0];
    if (!p)
        p = std::make_unique<ShaderProgram>(
            files_, height_fog ? "#define FROXEL_HEIGHT_FOG 1\n" : "#define FROXEL_HEIGHT_FOG 0\n");
    return *p;
}

FroxelPass::~FroxelPass() = default;

void FroxelPass::set_fog(const geometry::Medium* medium, const geometry::FroxelOptions& options)
{
    geometry::validate_froxel_options(options);
    if (medium && !(medium->max_extinction() > 0.0))
        medium = nullptr;
    if (medium != medium_ || (medium && medium_gpu_.set(medium))) {
        medium_gpu_.set(medium);
        shell_ = medium ? build_shell_mesh(*medium) : ShellMesh{};
        coarse_shells_ = {};
        tile_bounds_.set_shell(shell_);
        drawn_shell_ = 0;
    }
    medium_ = medium;
    options_ = options;
    if (!enabled_)
        stats_ = {};
    enabled_ = true;
    stats_.enabled = true;
}

void FroxelPass::clear()
{
    enabled_ = false;
    apply_ = false;
    classified_ = false;
    medium_ = nullptr;
    history_valid_ = false;
    key_.reset();
    stats_ = {};
}

void FroxelPass::extend_bounds(glm::dvec3& lo, glm::dvec3& hi) const
{
    if (!enabled_ || !medium_)
        return;
    lo = glm::min(lo, medium_->bounds().min);
    hi = glm::max(hi, medium_->bounds().max);
}

bool FroxelPass::visible(const FrameContext& frame) const
{
    if (options_.height_fog.enabled())
        return true;  // everywhere
    if (!medium_)
        return false;
    const geometry::Bounds3& b = medium_->bounds();
    if (frame.partitioned) {  // combined mode: the froxels draw nothing beyond near_end
        const glm::dvec3 eye(frame.eye);
        const glm::dvec3 nearest = glm::clamp(eye, b.min, b.max);
        if (glm::length(nearest - eye) > double(frame.partition.y) * 1.001 + 1.0)
            return false;
    }
    return box_in_view(frame, b.min, b.max);
}

void FroxelPass::bind_layout(const ShaderProgram& p) const
{
    p.set("u_fx_size", v_->size);
    p.set("u_fx_distribution", int(options_.distribution));
    p.set("u_fx_power", float(options_.power));
    p.set("u_fx_log2_scale", float(options_.log2_scale));
    p.set("u_fx_tiles", unit_tiles);
    p.set("u_fx_far", view_.far);
    p.set("u_fx_eye", view_.eye);
    p.set("u_fx_forward", view_.forward);
    p.set("u_fx_right", view_.right);
    p.set("u_fx_up", view_.up);
    glBindTextureUnit(unit_tiles, v_->tiles[current_].get());
}

void FroxelPass::prepare(const FrameContext& frame, const ShadowMapPass* shadow)
{
    for (PassTimer& timer : timers_)
        timer.forget();
    stats_.updated = false;
    stats_.converged = false;
    applied_pixels_ = 0;
    medium_gpu_.set_partition(frame.partitioned, frame.partition, frame.partition_depth);
    visible_ = enabled_ && visible(frame);
    stats_.visible = visible_;
    if (!visible_) {  // off-screen: no pass runs, no history survives
        apply_ = false;
        history_valid_ = false;
        key_.reset();
    }
    shadow_ = options_.terrain_shadows ? shadow : nullptr;
}

void FroxelPass::update(const FrameContext& frame, const TerrainPass& terrain, GLuint depth_texture)
{
    if (!visible_)
        return;
    const auto tiles = [&](int n) { return std::max(1, int(std::lround(n * resolution_))); };
    const glm::ivec3 size(tiles(options_.width), tiles(options_.height), options_.slices);
    if (v_->size != size) {
        v_->density = make_volume(size, GL_RGBA16F);
        v_->light = make_volume(size, GL_RGBA16F);
        v_->integrated = make_volume(size, GL_RGBA16F);
        for (int k = 0; k < 2; ++k) {
            v_->resolved[k] = make_volume(size, GL_RGBA16F);
            glTextureParameteri(v_->resolved[k].get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);  // the apply's J lookups
            glTextureParameteri(v_->resolved[k].get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
            v_->tiles[k] = make_tiles({size.x, size.y});
        }
        glTextureParameteri(v_->light.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(v_->light.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        v_->size = size;
        stats_.size = size;
        history_valid_ = false;
        key_.reset();
    }
    const geometry::FroxelOptions& o = options_;
    FroxelVolumeKey key = make_froxel_volume_key(frame, terrain.identity(), medium_, o);
    key.light_volume = baked_light() && light_volume_ && light_volume_->ready() ? light_volume_->volume() : nullptr;
    // A rebuilt shadow map (or none) lights the volume differently.
    const int shadow_version = shadow_ ? shadow_->updates() : -1;
    const bool same_view = key_ == key && apply_ && shadow_version == shadow_version_;
    if (same_view && (converged_ || !o.temporal)) {
        stats_.converged = true;
        return;  // the volume is as good as it gets: reuse it
    }
    // A still: the view held since the last frame, or the first view of this fog. It takes its
    // jittered samples at once and needs no history; a moving view takes one and the filter
    // blends it with the reprojected history.
    const bool still = o.temporal && (same_view || !key_);
    // The history stays usable across view, sun and fog changes (reprojection and the clamp
    // take care of them), not across a change of the volume's layout.
    const FroxelVolumeLayout layout = volume_layout(o);
    history_valid_ = history_valid_ && o.temporal && layout_ == layout;
    layout_ = layout;
    // A sun that turned by more than half a degree, or light that changed by more than 2 %,
    // changes J everywhere at once: the clamp alone would let the old light linger.
    const glm::vec3 light[3] = {frame.sun_direction, frame.sun_radiance, frame.ambient};
    const bool light_jumped = glm::dot(light[0], light_[0]) < std::cos(0.5f * 3.14159265f / 180.0f) ||
        glm::length(light[1] - light_[1]) > 0.02f * glm::length(light[1]) ||
        glm::length(light[2] - light_[2]) > 0.02f * glm::length(light[2]);
    history_valid_ = history_valid_ && !light_jumped;
    std::copy(std::begin(light), std::end(light), std::begin(light_));
    key_ = std::move(key);
    shadow_version_ = shadow_version;
    apply_ = true;  // before the passes: the classification reads the volume as the apply does
    run_passes(frame, depth_texture, still);
    converged_ = still || !o.temporal;
    stats_.updated = true;
    stats_.converged = converged_;
    ++stats_.updates;
}

void FroxelPass::apply(const FrameContext& frame, GLuint color_texture, GLuint depth_texture,
                       const FrameSamples& samples)
{
    if (!visible_ || !apply_)
        return;
    {
        const ScopedPassTimer timed(timers_[marches]);
        run_pixel_fog(frame, depth_texture, color_texture, applied_);
    }
    bool split = false;
    {
        const ScopedPassTimer timed(timers_[splits]);
        split = run_splits(frame, depth_texture, samples, applied_);
    }
    if (!split)
        timers_[splits].forget();
    const ScopedPassTimer timed(timers_[apply_stage]);
    const ShaderProgram& p = apply_program_;
    p.set("u_fog", 0);
    p.set("u_splits", int(split));
    p.set("u_split", 1);
    p.set("u_split_fog", 2);
    p.set("u_size", glm::ivec2(frame.width, frame.height));
    p.use();
    glBindTextureUnit(0, applied_.fog.get());
    glBindTextureUnit(1, applied_.split.get());
    glBindTextureUnit(2, applied_.split_fog.get());
    glBindImageTexture(0, color_texture, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
    glDispatchCompute(GLuint((frame.width + 31) / 32), GLuint((frame.height + 7) / 8), 1);
    glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    applied_pixels_ = frame.width * frame.height;
}

void FroxelPass::run_passes(const FrameContext& frame, GLuint depth_texture, bool still)
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
    run_classify(frame, depth_texture);
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
    const glm::dmat4& V = frame.view;
    view_.forward = glm::vec3(-V[0][2], -V[1][2], -V[2][2]);
    view_.right = glm::vec3(V[0][0], V[1][0], V[2][0]) / float(frame.projection[0][0]);
    view_.up = glm::vec3(V[0][1], V[1][1], V[2][1]) / float(frame.projection[1][1]);
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
    bind_layout(density_);
    medium_gpu_.bind(density_, options_.height_fog, unit_medium);
    density_.set("u_samples", options_.density_samples);
    density_.use();
    glBindImageTexture(0, v_->density.get(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    dispatch_volume(v_->size, v_->size.z);
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
    p.set("u_sun_direction", sun_march_direction(frame.sun_direction));
    p.set("u_sun_radiance", frame.sun_radiance);
    p.set("u_ambient", frame.ambient);
    p.set("u_air", glm::vec4(frame.sky_horizon, frame.haze_density));
    const double albedo = medium_ ? medium_->options().albedo : 0.0, g = medium_ ? medium_->options().anisotropy : 0.0;
    p.set("u_albedo", glm::vec2(float(albedo), float(haze.albedo)));
    p.set("u_anisotropy", glm::vec2(float(g), float(haze.anisotropy)));
    p.set("u_fog_shadows", int(o.fog_shadows));
    p.set(
        "u_octaves",
        geometry::shader_octaves(geometry::multiple_scattering_of(medium_), geometry::scattering_octaves_of(medium_)));
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
    bind_layout(lighting_);
    bind_light(lighting_, frame);
    lighting_.set("u_density", unit_density);
    lighting_.set("u_jitter", jitter.froxel);
    lighting_.set("u_sun_jitter", jitter.sun);
    lighting_.set("u_whole_tiles", int(options_.fog_aware));
    lighting_.use();
    glBindTextureUnit(unit_density, v_->density.get());
    glBindImageTexture(0, v_->light.get(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    dispatch_volume(v_->size, v_->size.z);
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
    const ShaderProgram& p = integrate_.get(options_.height_fog.enabled());
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

void FroxelPass::run_classify(const FrameContext& frame, GLuint depth_texture)
{
    // Worth it where most pixels' marches are long: the eye inside the Medium's shell (every
    // ray marches from the eye) or a height fog (every ray marches its haze). Seen from outside
    // without one, the pixels that could read the volume see no fog and already stop at once
    // (on gabilan.bil and Mandakini.bil the same pictures, the classification's cost on top).
    classified_ = options_.fog_aware && (!shell_ok_ || options_.height_fog.enabled());
    if (!classified_)
        return;  // the standard apply reads the volume everywhere; fog-aware, every pixel marches
    const ScopedPassTimer timed(timers_[classify]);
    const ShaderProgram& p = classify_.get(options_.height_fog.enabled());
    classified_ = false;  // the apply's library: every pixel's taps still to be decided
    bind_apply(p);
    bind_light(p, frame);
    classified_ = true;
    p.set("u_depth", 0);
    p.set("u_raster", glm::ivec2(frame.width, frame.height));
    const glm::vec2 planes = depth_planes(frame);
    p.set("u_near_plane", planes.x);
    p.set("u_far_plane", planes.y);
    p.set("u_tolerance", classify_tolerance);
    p.set("u_edge_slices", classify_edge_slices);
    p.set("u_missed", classify_missed);
    p.use();
    glBindTextureUnit(0, depth_texture);
    glBindImageTexture(0, v_->tiles[current_].get(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    glDispatchCompute(GLuint((v_->size.x + 7) / 8), GLuint((v_->size.y + 7) / 8), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

void FroxelPass::bind_apply(const ShaderProgram& p) const
{
    // Every sampler on its own unit, even unused ones: types may not share a unit.
    p.set("u_fx_tiles", unit_tiles);
    p.set("u_fx_volume", unit_volume);
    p.set("u_fx_shell_depths", unit_shell_depths);
    p.set("u_md_grid", unit_medium);
    p.set("u_md_noise", unit_medium + 1);
    p.set("u_fx_apply", visible_ && apply_ ? (options_.fog_aware ? 2 : 1) : 0);
    p.set("u_fx_classified", int(classified_));
    if (!visible_ || !apply_)
        return;
    bind_layout(p);
    medium_gpu_.bind(p, options_.height_fog, unit_medium);
    p.set("u_fx_view_projection", view_.view_projection);
    p.set("u_fx_shell", int(shell_ok_));
    p.set("u_fx_near", view_.near);
    p.set("u_fx_pixel_steps", marched_steps());
    glBindTextureUnit(unit_volume, v_->integrated.get());
    glBindTextureUnit(unit_shell_depths, tile_bounds_.shell_depths());
}

void FroxelPass::append_timings(std::vector<PassTime>& out) const
{
    stats_.applied_pixels = applied_pixels_;
    stats_.marched_pixels = stats_.upsampled_pixels = stats_.edge_pixels = stats_.fog_split_pixels = 0;
    if (applied_pixels_ > 0) {
        const PixelFog::Counts c = applied_.read_counts();
        stats_.marched_pixels = c.marched;
        stats_.upsampled_pixels = c.upsampled;
        stats_.edge_pixels = c.split;
        stats_.fog_split_pixels = c.fog_split;
    }
    for (const PassTimer& timer : timers_)
        if (timer.ran())
            out.push_back(timer.result());
}

}  // namespace kiri::render::detail
