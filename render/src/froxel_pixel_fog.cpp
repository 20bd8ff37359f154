// FroxelPass's per-pixel fog (froxel_upsample.comp, froxel_pixels.comp): what the apply puts on
// the frame and read_fog reads back, by the same passes.
#include "froxel_pass.hpp"

#include <array>
#include <cstddef>
#include <memory>
#include <vector>

#include <glm/common.hpp>

#include "flip_rows.hpp"
#include "staged_read.hpp"
#include "terrain_pass.hpp"

namespace kiri::render::detail {
namespace {

// The fog's samplers stay clear of the apply's units (froxel_pass_parts.hpp: 5..19).
// The split pixels' multisampled depth and colour share the units of the grids' samples and the
// background, which their programs do not read.
constexpr int unit_frame_depth = 0, unit_samples = 1, unit_background = 2, unit_sample_info = 3, unit_split_ray = 4,
              unit_ms_depth = unit_samples, unit_ms_color = unit_background;
// A pixel's samples split by their fog where the largest gap between what the fog before their
// surfaces lets through exceeds this (froxel_edges.comp).
constexpr float fog_split = 0.05f;

// The list's header (froxel_frame.glsl, FrameMarches): the indirect dispatch, then the counts.
struct MarchHeader {
    GLuint groups[3] = {0, 1, 1}, unused = 0;
    GLuint listed = 0, sampled = 0, upsampled = 0, unused2 = 0;
};
static_assert(sizeof(MarchHeader) == 32);

// A list of `entries` points after its header.
Buffer make_march_list(std::size_t entries)
{
    Buffer list = make_buffer();
    glNamedBufferStorage(list.get(), GLsizeiptr(sizeof(MarchHeader) + sizeof(GLuint) * entries), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    return list;
}

// The list emptied: no points, no groups to dispatch.
void clear_march_list(const Buffer& list)
{
    const MarchHeader header;
    glNamedBufferSubData(list.get(), 0, sizeof header, &header);
}

// Points across and down of the grid at `spacing` (froxel_frame.glsl's frame_grid).
glm::ivec2 grid_points(const glm::ivec2& size, int spacing)
{
    return spacing == 1 ? size : (glm::max(size, glm::ivec2(2)) - 2) / spacing + 2;
}

Texture make_fog_image(const glm::ivec2& size)
{
    Texture t = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(t.get(), 1, GL_RGBA32F, size.x, size.y);
    glTextureParameteri(t.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
}

}  // namespace

void FroxelPass::PixelFog::resize(int w, int h)
{
    if (w == width && h == height)
        return;
    width = w;
    height = h;
    const glm::ivec2 size(w, h);
    for (std::size_t k = 0; k < sample_spacings.size(); ++k) {
        samples[k] = make_fog_image(grid_points(size, sample_spacings[k]));
        info[k] = make_fog_image(grid_points(size, sample_spacings[k]));
    }
    background = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(background.get(), 1, GL_RGBA16F, w, h);
    const float black[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearTexImage(background.get(), 0, GL_RGBA, GL_FLOAT, black);
    fog = make_fog_image(size);
    split = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(split.get(), 1, GL_R8, w, h);
    glTextureParameteri(split.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(split.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    split_ray = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(split_ray.get(), 1, GL_RG32F, w, h);
    glTextureParameteri(split_ray.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(split_ray.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    split_fog = make_fog_image(size);
    // Each pixel is listed once at most.
    split_list = make_march_list(std::size_t(w) * h);
    lookups = make_march_list(std::size_t(w) * h);
    splits_run = false;
    // Refinement k lists points of the grid at half the spacing of grid k.
    for (std::size_t k = 0; k < sample_spacings.size(); ++k) {
        const glm::ivec2 n = grid_points(size, sample_spacings[k] / 2);
        lists[k] = make_march_list(std::size_t(n.x) * n.y);
    }
}

FroxelPass::PixelFog::Counts FroxelPass::PixelFog::read_counts() const
{
    Counts c;
    if (!lists[0])
        return c;
    // Every list's header in one staged read: one wait for the GPU a frame, not one a list.
    std::array<GLuint, sample_spacings.size() + 1> sources{};
    for (std::size_t k = 0; k < lists.size(); ++k)
        sources[k] = lists[k].get();
    const bool splits = splits_run && split_list;
    const std::size_t n = lists.size() + (splits ? 1 : 0);
    if (splits)
        sources[lists.size()] = split_list.get();
    std::array<MarchHeader, sample_spacings.size() + 1> h;
    staging.read({sources.data(), n}, sizeof(MarchHeader), h.data());
    for (std::size_t k = 0; k < lists.size(); ++k) {
        c.marched += int(h[k].sampled + h[k].listed);
        c.upsampled += int(h[k].upsampled);
    }
    if (splits) {
        // A pixel split by its fog on one surface is counted in `sampled` too.
        c.split = int(h[lists.size()].listed);
        c.fog_split = int(h[lists.size()].sampled);
    }
    return c;
}

namespace {

// froxel_frame.glsl's frame: its depth on unit_frame_depth, its size and projection.
void set_frame(const ShaderProgram& p, const FrameContext& frame)
{
    const glm::vec2 planes = depth_planes(frame);
    p.set("u_depth", unit_frame_depth);
    p.set("u_size", glm::ivec2(frame.width, frame.height));
    p.set("u_near_plane", planes.x);
    p.set("u_far_plane", planes.y);
}

}  // namespace

void FroxelPass::bind_pixel_program(const ShaderProgram& p, const FrameContext& frame, int spacing) const
{
    bind_apply(p);
    bind_light(p, frame);  // every sampler on its own unit, used or not
    set_frame(p, frame);
    p.set("u_spacing", spacing);
    p.set("u_split_ray", unit_split_ray);
    p.set("u_ms_depth", unit_ms_depth);
    p.set("u_ms_color", unit_ms_color);
    p.set("u_split", 0);
}

// The split pixels' inputs and the tiles on the units the pixels' program declares them, bound
// in each of its stages: llvmpipe compiles a program's variant for each set of textures and images
// bound to its units, and the marches and the split pixels' samples, the same program, each took
// their own (about 1.5 s of a new user's first frame at 1280x720, or of the first after a change).
void FroxelPass::bind_stage_inputs(const PixelFog& out, const FrameSamples* samples) const
{
    glBindTextureUnit(unit_split_ray, out.split_ray.get());
    if (samples && samples->depth != 0 && samples->color != 0) {
        glBindTextureUnit(unit_ms_depth, samples->depth);
        glBindTextureUnit(unit_ms_color, samples->color);
    }
    glBindImageTexture(2, v_->tiles[current_].get(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
}

void FroxelPass::bind_tile_rays()
{
    const int tiles = v_->size.x * v_->size.y;
    if (!tile_rays_ || tile_rays_capacity_ < tiles) {
        tile_rays_ = make_march_list(std::size_t(tiles));
        tile_rays_capacity_ = tiles;
    }
    clear_march_list(tile_rays_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, tile_rays_.get());
}

void FroxelPass::run_tile_rays(const FrameContext& frame, GLuint depth_texture, const FrameSamples* samples,
                               float missed)
{
    applied_.resize(frame.width, frame.height);
    const ShaderProgram& pixels = program(pixels_);
    bind_pixel_program(pixels, frame, 1);
    pixels.set("u_stage", 2);
    pixels.set("u_missed", missed);
    pixels.use();
    glBindTextureUnit(unit_frame_depth, depth_texture);
    bind_stage_inputs(applied_, samples);
    // Images of the formats the marches bind there (unwritten in this stage).
    glBindImageTexture(0, applied_.fog.get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glBindImageTexture(1, applied_.info.back().get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    dispatch_listed(tile_rays_.get());
}

bool FroxelPass::run_splits(const FrameContext& frame, GLuint depth_texture, const FrameSamples& samples, PixelFog& out)
{
    out.splits_run = false;
    // Only where pixels march (the fog-aware apply), and only in a frame drawn at the still's
    // resolution: a frame the preview draws small while the view moves has more split pixels for
    // its size and no time for their marches.
    const bool marching = visible_ && apply_ && options_.fog_aware;
    if (!marching || resolution_ < 1.0 || samples.count < 2 || samples.color == 0 || samples.depth == 0 ||
        !samples.offsets)
        return false;
    const int count = std::min(samples.count, 8);
    clear_march_list(out.split_list);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, out.split_list.get());
    // The pixels whose samples see different fog (two surfaces, or one fogged unevenly), listed
    // with bounds of their rays' stretch of the shell.
    const ShaderProgram& e = edges_;
    bind_pixel_program(e, frame, 1);
    e.set("u_fog_split", fog_split);
    e.set("u_samples", count);
    glProgramUniform2fv(e.id(), e.location("u_offsets"), 8, samples.offsets);
    e.use();
    glBindTextureUnit(unit_frame_depth, depth_texture);
    glBindTextureUnit(unit_ms_depth, samples.depth);
    glBindImageTexture(0, out.split.get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R8);
    glBindImageTexture(1, out.split_ray.get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
    glDispatchCompute(GLuint((frame.width + 7) / 8), GLuint((frame.height + 7) / 8), 1);
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                    GL_TEXTURE_FETCH_BARRIER_BIT);
    // Their samples' marches, each along its own ray to its own surface (froxel_pixels.comp's
    // stage 1 with u_split), their mean into out.split_fog.
    const ShaderProgram& pixels = program(pixels_);
    bind_pixel_program(pixels, frame, 1);
    pixels.set("u_stage", 1);
    pixels.set("u_split", 1);
    pixels.set("u_samples", count);
    glProgramUniform2fv(pixels.id(), pixels.location("u_offsets"), 8, samples.offsets);
    pixels.use();
    glBindTextureUnit(unit_frame_depth, depth_texture);
    bind_stage_inputs(out, &samples);
    glBindImageTexture(0, out.split_fog.get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glBindImageTexture(1, out.info.back().get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);  // unwritten here
    dispatch_listed(out.split_list.get());
    out.splits_run = true;
    return true;
}

void FroxelPass::run_pixel_fog(const FrameContext& frame, GLuint depth_texture, GLuint color_texture, PixelFog& out,
                               const FrameSamples* samples)
{
    out.resize(frame.width, frame.height);
    const bool marching = visible_ && apply_ && options_.fog_aware;
    const float tolerance = marching ? upsample_tolerance() : 0.0f;
    // The frame before its fog, which only the means are judged over: for this run and a later
    // read_fog's.
    if (color_texture != 0 && tolerance > 0.0f)
        glCopyImageSubData(color_texture, GL_TEXTURE_2D, 0, 0, 0, 0, out.background.get(), GL_TEXTURE_2D, 0, 0, 0, 0,
                           frame.width, frame.height, 1);
    for (const Buffer& list : out.lists)
        clear_march_list(list);
    glBindTextureUnit(unit_frame_depth, depth_texture);
    const glm::ivec2 size(frame.width, frame.height);
    bind_stage_inputs(out, samples);
    // The grid at `spacing` into `image` (its points' info into `info`, 0: none) from the one at
    // twice it (`coarser`, its points' info `coarser_info`), listing into `list` the points that
    // march, then marching them.
    const auto refine = [&](int spacing, GLuint coarser, GLuint coarser_info, GLuint image, GLuint info, GLuint list) {
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, list);
        clear_march_list(out.lookups);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, out.lookups.get());
        const ShaderProgram& upsample = program(upsample_);
        bind_pixel_program(upsample, frame, spacing);
        upsample.set("u_fx_samples", unit_samples);
        upsample.set("u_fx_sample_info", unit_sample_info);
        upsample.set("u_fx_write_info", int(info != 0));
        // A share of the tolerance as fine as the grid is coarse: a coarser grid's means' errors
        // carry into every finer grid's means.
        upsample.set("u_fx_upsample", tolerance / float(spacing));
        upsample.set("u_background", unit_background);
        upsample.use();
        glBindTextureUnit(unit_samples, coarser);
        glBindTextureUnit(unit_background, out.background.get());
        glBindTextureUnit(unit_sample_info, coarser_info);
        glBindImageTexture(0, image, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glBindImageTexture(1, info != 0 ? info : coarser_info, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        const glm::ivec2 n = grid_points(size, spacing);
        glDispatchCompute(GLuint((n.x + 31) / 32), GLuint((n.y + 7) / 8), 1);
        glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, 0);
        // The points the volume resolves read it (froxel_lookup.comp).
        bind_pixel_program(lookup_, frame, spacing);
        lookup_.use();
        glBindImageTexture(0, image, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        dispatch_listed(out.lookups.get());
        if (!marching)
            return;
        const ShaderProgram& pixels = program(pixels_);
        bind_pixel_program(pixels, frame, spacing);
        pixels.set("u_stage", 1);
        pixels.use();
        glBindImageTexture(0, image, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        dispatch_listed(list);
    };
    if (tolerance > 0.0f) {
        // The coarsest grid's points march (or read the volume); every finer grid's points take
        // the mean of the coarser points around them where they agree, else march.
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, out.lists[0].get());
        const ShaderProgram& pixels = program(pixels_);
        const int coarsest = sample_spacings[0];
        bind_pixel_program(pixels, frame, coarsest);
        pixels.set("u_stage", 0);
        pixels.use();
        glBindImageTexture(0, out.samples[0].get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glBindImageTexture(1, out.info[0].get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        const glm::ivec2 n = grid_points(size, coarsest);
        glDispatchCompute(GLuint((n.x * n.y + 63) / 64), 1, 1);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
        for (std::size_t k = 1; k < sample_spacings.size(); ++k)
            refine(sample_spacings[k], out.samples[k - 1].get(), out.info[k - 1].get(), out.samples[k].get(),
                   out.info[k].get(), out.lists[k - 1].get());
    }
    refine(1, out.samples.back().get(), out.info.back().get(), out.fog.get(), 0, out.lists.back().get());
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
}

FogBuffer FroxelPass::read_fog(const FrameContext& frame, const TerrainPass& terrain)
{
    FogBuffer out;
    if (!enabled_ || frame.width <= 0 || frame.height <= 0)
        return out;
    if (!depth_program_)
        depth_program_ =
            std::make_unique<ShaderProgram>(std::initializer_list<std::string_view>{"terrain.vert", "depth_only.frag"});
    // The terrain's depth at pixel centres, where the terrain's fragments applied the fog (the
    // multisampled frame's resolved depth holds one sample, off the centre).
    Texture surface = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(surface.get(), 1, GL_DEPTH_COMPONENT32F, frame.width, frame.height);
    glTextureParameteri(surface.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(surface.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    Framebuffer fbo = make_framebuffer();
    glNamedFramebufferTexture(fbo.get(), GL_DEPTH_ATTACHMENT, surface.get(), 0);
    glNamedFramebufferDrawBuffer(fbo.get(), GL_NONE);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.get());
    glViewport(0, 0, frame.width, frame.height);
    const float far_depth = 1.0f;
    glClearNamedFramebufferfv(fbo.get(), GL_DEPTH, 0, &far_depth);
    depth_program_->set("u_view_projection", frame.view_projection);
    depth_program_->use();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    terrain.draw_mesh();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    const GLuint depth_texture = surface.get();
    // Judged over the last frame's colour before its fog: the apply's (as sized as this frame)
    PixelFog& pixel_fog = applied_;
    run_pixel_fog(frame, depth_texture, 0, pixel_fog);
    const ShaderProgram& p = readback_;
    Texture image = make_texture(GL_TEXTURE_2D), depth = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(image.get(), 1, GL_RGBA32F, frame.width, frame.height);
    glTextureStorage2D(depth.get(), 1, GL_R32F, frame.width, frame.height);
    p.set("u_depth", 0);
    p.set("u_fog", 1);
    p.set("u_size", glm::ivec2(frame.width, frame.height));
    const glm::vec2 planes = depth_planes(frame);
    p.set("u_near_plane", planes.x);
    p.set("u_far_plane", planes.y);
    p.use();
    glBindTextureUnit(0, depth_texture);
    glBindTextureUnit(1, pixel_fog.fog.get());
    glBindImageTexture(0, image.get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glBindImageTexture(1, depth.get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    glDispatchCompute(GLuint((frame.width + 7) / 8), GLuint((frame.height + 7) / 8), 1);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    auto read = [&](GLuint texture, GLenum format, int channels, std::vector<float>& into) {
        into.resize(std::size_t(frame.width) * frame.height * channels);
        glGetTextureImage(texture, 0, format, GL_FLOAT, GLsizei(into.size() * sizeof(float)), into.data());
        flip_rows(into, std::size_t(frame.width) * channels);
    };
    out.width = frame.width;
    out.height = frame.height;
    read(image.get(), GL_RGBA, 4, out.rgba);
    read(depth.get(), GL_RED, 1, out.depth);
    return out;
}

}  // namespace kiri::render::detail
