// FroxelPass's per-pixel fog (froxel_upsample.comp, froxel_pixels.comp): what the apply puts on
// the frame and read_fog reads back, by the same passes.
#include "froxel_pass.hpp"

namespace kiri::render::detail {
namespace {

// The fog's samplers stay clear of the apply's units (froxel_pass.cpp: 5..19).
constexpr int unit_frame_depth = 0, unit_samples = 1, unit_background = 2;

// The list's header (froxel_frame.glsl, FrameMarches): the indirect dispatch, then the counts.
struct MarchHeader {
    GLuint groups[3] = {0, 1, 1}, unused = 0;
    GLuint listed = 0, sampled = 0, upsampled = 0, unused2 = 0;
};
static_assert(sizeof(MarchHeader) == 32);

Texture make_fog_image(int width, int height)
{
    Texture t = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(t.get(), 1, GL_RGBA32F, width, height);
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
    samples = make_fog_image(w / 2 + 1, h / 2 + 1);
    background = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(background.get(), 1, GL_RGBA16F, w, h);
    const float black[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearTexImage(background.get(), 0, GL_RGBA, GL_FLOAT, black);
    fog = make_fog_image(w, h);
    list = make_buffer();
    glNamedBufferStorage(list.get(), GLsizeiptr(sizeof(MarchHeader) + sizeof(GLuint) * std::size_t(w) * h), nullptr,
                         GL_DYNAMIC_STORAGE_BIT | GL_MAP_READ_BIT);
}

std::pair<int, int> FroxelPass::PixelFog::counts() const
{
    if (!list)
        return {0, 0};
    MarchHeader h;
    glGetNamedBufferSubData(list.get(), 0, sizeof h, &h);
    return {int(h.sampled + h.listed), int(h.upsampled)};
}

void FroxelPass::run_pixel_fog(const FrameContext& frame, GLuint depth_texture, GLuint color_texture, PixelFog& out)
{
    out.resize(frame.width, frame.height);
    if (color_texture != 0)  // the frame's before its fog, for this run and a later read_fog's
        glCopyImageSubData(color_texture, GL_TEXTURE_2D, 0, 0, 0, 0, out.background.get(), GL_TEXTURE_2D, 0, 0, 0, 0,
                           frame.width, frame.height, 1);
    const MarchHeader header;
    glNamedBufferSubData(out.list.get(), 0, sizeof header, &header);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, out.list.get());
    glBindTextureUnit(unit_frame_depth, depth_texture);
    const glm::vec2 planes = depth_planes(frame);
    const bool haze = options_.height_fog.enabled();
    const bool marching = visible_ && apply_ && options_.fog_aware;
    const float tolerance = marching ? float(options_.upsample) : 0.0f;
    const auto bind = [&](const ShaderProgram& p) {
        bind_apply(p);
        bind_light(p, frame);  // every sampler on its own unit, used or not
        p.set("u_depth", unit_frame_depth);
        p.set("u_size", glm::ivec2(frame.width, frame.height));
        p.set("u_near_plane", planes.x);
        p.set("u_far_plane", planes.y);
    };
    if (tolerance > 0.0f) {  // the half-resolution samples
        const ShaderProgram& pixels = pixels_.get(haze);
        bind(pixels);
        pixels.set("u_stage", 0);
        pixels.use();
        glBindImageTexture(0, out.samples.get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        const int n = (frame.width / 2 + 1) * (frame.height / 2 + 1);
        glDispatchCompute(GLuint((n + 63) / 64), 1, 1);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    }
    const ShaderProgram& upsample = upsample_.get(haze);
    bind(upsample);
    upsample.set("u_fx_samples", unit_samples);
    upsample.set("u_fx_upsample", tolerance);
    upsample.set("u_background", unit_background);
    upsample.use();
    glBindTextureUnit(unit_samples, out.samples.get());
    glBindTextureUnit(unit_background, out.background.get());
    glBindImageTexture(0, out.fog.get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glDispatchCompute(GLuint((frame.width + 31) / 32), GLuint((frame.height + 7) / 8), 1);
    if (marching) {  // the pixels left to march, one invocation each
        glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        const ShaderProgram& pixels = pixels_.get(haze);
        bind(pixels);
        pixels.set("u_stage", 1);
        pixels.use();
        glBindImageTexture(0, out.fog.get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, out.list.get());
        glDispatchComputeIndirect(0);
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
}

}  // namespace kiri::render::detail
