#include "froxel_pass.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>

#include "kiri/geometry/medium/fog_lighting.hpp"
#include "kiri/geometry/medium/medium.hpp"
#include "froxel_pass_parts.hpp"
#include "sun_volume.hpp"
#include "terrain_pass.hpp"

namespace kiri::render::detail {
namespace {

using namespace froxel_parts;

const char* const stage_names[stage_count] = {
    "froxel shell",     "froxel tiles",    "froxel density", "froxel lighting", "froxel temporal",
    "froxel integrate", "froxel classify", "froxel marches", "froxel splits",   "froxel apply"};

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

// The libraries of a program that lights fog (froxel_light.glsl), then its stage file.
std::vector<std::string_view> light_libraries(std::string_view stage)
{
    return {"view_depth.glsl",
            "fog_partition.glsl",
            "froxel_common.glsl",
            "fog_lighting.glsl",
            "medium_shell.glsl",
            "height_fog.glsl",
            "froxel_medium.glsl",
            "sun_march.glsl",
            "sun_volume.glsl",
            "terrain_shadow.glsl",
            "light_volume.glsl",
            "froxel_light.glsl",
            stage};
}

// `files`, then a pass over the froxels of the tiles with fog (froxel_fog_tiles.glsl, among them).
std::vector<std::string_view> fog_tiles_libraries(std::vector<std::string_view> files, std::string_view stage)
{
    files.push_back(stage);
    return files;
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

// Those of the classification (froxel_classify.comp): the frame's pixels and the list of the tiles
// it leaves to the pixels' program (froxel_frame.glsl).
std::vector<std::string_view> classify_libraries()
{
    std::vector<std::string_view> files = march_libraries("froxel_frame.glsl");
    files.push_back("froxel_classify.comp");
    return files;
}

// Those of the pass that finds the pixels whose samples see different fog (froxel_edges.comp).
std::vector<std::string_view> edge_libraries()
{
    std::vector<std::string_view> files = pixel_libraries("depth_samples.glsl");
    files.insert(files.end(), {"froxel_fog_before.glsl", "froxel_edges.comp"});
    return files;
}

// Those of the pixels' marches (froxel_pixels.comp), whose split samples bound their own rays by
// the fog before their surfaces.
std::vector<std::string_view> split_libraries()
{
    std::vector<std::string_view> files = pixel_libraries("froxel_fog_before.glsl");
    files.push_back("froxel_pixels.comp");
    return files;
}

}  // namespace

FroxelPass::FroxelPass()
    : v_(std::make_unique<Volumes>()),
      fog_tiles_({"froxel_common.glsl", "froxel_fog_tiles.glsl", "froxel_fog_tiles.comp"}),
      density_({"fog_partition.glsl", "froxel_common.glsl", "fog_lighting.glsl", "medium_shell.glsl", "height_fog.glsl",
                "froxel_medium.glsl", "froxel_fog_tiles.glsl", "froxel_density.comp"}),
      lighting_(fog_tiles_libraries(light_libraries("froxel_fog_tiles.glsl"), "froxel_lighting.comp")),
      temporal_({"froxel_common.glsl", "froxel_temporal.comp"}),
      accumulate_({"froxel_common.glsl", "froxel_accumulate.comp"}),
      opaque_({"fog_partition.glsl", "froxel_common.glsl", "fog_lighting.glsl", "medium_shell.glsl", "height_fog.glsl",
               "froxel_medium.glsl", "froxel_opaque.comp"}),
      integrate_(light_libraries("froxel_integrate.comp")), classify_(classify_libraries()), pixels_(split_libraries()),
      upsample_(pixel_libraries("froxel_upsample.comp")), apply_program_({"froxel_apply.comp"}),
      readback_({"view_depth.glsl", "froxel_frame.glsl", "froxel_readback.comp"}), edges_(edge_libraries()),
      lookup_(pixel_libraries("froxel_lookup.comp"))
{
    for (const char* name : stage_names)
        timers_.emplace_back(name);
}

const ShaderProgram& FroxelPass::Variants::get(bool height_fog, bool light_volume)
{
    std::unique_ptr<ShaderProgram>& p = programs_[(height_fog ? 1 : 0) + (light_volume ? 2 : 0)];
    if (!p)
        p = std::make_unique<ShaderProgram>(files_,
                                            std::string("#define FROXEL_HEIGHT_FOG ") + (height_fog ? "1" : "0") +
                                                "\n" + std::string(light_volume_preamble(light_volume)));
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

void FroxelPass::update(const FrameContext& frame, const TerrainPass& terrain, GLuint depth_texture,
                        const FrameSamples* samples)
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
        v_->fog_tiles = make_buffer();
        glNamedBufferStorage(v_->fog_tiles.get(), GLsizeiptr(sizeof(glm::uvec4) + sizeof(GLuint) * size.x * size.y),
                             nullptr, GL_DYNAMIC_STORAGE_BIT);
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
    run_passes(frame, depth_texture, still, samples);
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
        run_pixel_fog(frame, depth_texture, color_texture, applied_, &samples);
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
