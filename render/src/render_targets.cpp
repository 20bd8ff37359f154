#include "render_targets.hpp"

#include <algorithm>
#include <string>

#include <glm/vec2.hpp>

#include "kiri/geometry/core/error.hpp"

#include "depth_pass.hpp"
#include "flip_rows.hpp"
#include "shader_program.hpp"

namespace kiri::render::detail {

void attach_sample_blends(GLuint fbo, Texture (&blends)[3], int width, int height, GLenum format, bool at_samples)
{
    for (int s = 0; s < 3; ++s) {
        blends[s] = Texture{};
        if (!at_samples)
            continue;
        blends[s] = make_texture(GL_TEXTURE_2D);
        glTextureStorage2D(blends[s].get(), 1, format, width, height);
        glTextureParameteri(blends[s].get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(blends[s].get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glNamedFramebufferTexture(fbo, GLenum(GL_COLOR_ATTACHMENT1 + s), blends[s].get(), 0);
    }
    const GLenum buffers[4] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3};
    glNamedFramebufferDrawBuffers(fbo, at_samples ? 4 : 1, buffers);
}

namespace {
void check_complete(GLuint framebuffer, const char* which)
{
    const GLenum status = glCheckNamedFramebufferStatus(framebuffer, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw Error(std::string("OpenGL: the ") + which + " framebuffer is incomplete (status " +
                    std::to_string(status) + ")");
}
}  // namespace

void RenderTargets::ensure(int width, int height)
{
    if (width == width_ && height == height_)
        return;
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
    if (width <= 0 || height <= 0 || width > max_size || height > max_size)
        throw Error("image size " + std::to_string(width) + "x" + std::to_string(height) +
                    " is outside what this OpenGL supports (1.." + std::to_string(max_size) + ")");
    msaa_color_ = make_texture(GL_TEXTURE_2D_MULTISAMPLE);
    msaa_depth_ = make_texture(GL_TEXTURE_2D_MULTISAMPLE);
    display_color_ = make_renderbuffer();
    resolved_color_ = make_texture(GL_TEXTURE_2D);
    resolved_depth_ = make_texture(GL_TEXTURE_2D);
    glTextureStorage2DMultisample(msaa_color_.get(), samples, GL_RGBA16F, width, height, GL_TRUE);
    glTextureStorage2DMultisample(msaa_depth_.get(), samples, GL_DEPTH_COMPONENT32F, width, height, GL_TRUE);
    glNamedRenderbufferStorage(display_color_.get(), GL_RGBA8, width, height);
    for (const Texture* t : {&resolved_color_, &resolved_depth_}) {
        glTextureStorage2D(t->get(), 1, t == &resolved_color_ ? GL_RGBA16F : GL_DEPTH_COMPONENT32F, width, height);
        glTextureParameteri(t->get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(t->get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTextureParameteri(t->get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(t->get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    msaa_ = make_framebuffer();
    resolved_ = make_framebuffer();
    display_ = make_framebuffer();
    glNamedFramebufferTexture(msaa_.get(), GL_COLOR_ATTACHMENT0, msaa_color_.get(), 0);
    glNamedFramebufferTexture(msaa_.get(), GL_DEPTH_ATTACHMENT, msaa_depth_.get(), 0);
    glNamedFramebufferTexture(resolved_.get(), GL_COLOR_ATTACHMENT0, resolved_color_.get(), 0);
    glNamedFramebufferTexture(resolved_.get(), GL_DEPTH_ATTACHMENT, resolved_depth_.get(), 0);
    glNamedFramebufferRenderbuffer(display_.get(), GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, display_color_.get());
    glNamedFramebufferTexture(display_.get(), GL_DEPTH_ATTACHMENT, resolved_depth_.get(), 0);
    check_complete(msaa_.get(), "multisampled");
    check_complete(resolved_.get(), "resolve");
    check_complete(display_.get(), "display");
    width_ = width;
    height_ = height;
    prepare_depth_resolve();
}

void RenderTargets::prepare_depth_resolve()
{
    if (!depth_resolve_) {
        depth_resolve_ = std::make_shared<ShaderProgram>(std::initializer_list<std::string_view>{
            "view_depth.glsl", "depth_samples.glsl", "fullscreen.vert", "depth_resolve.frag"});
        empty_vao_ = make_vertex_array();
    }
    // Where the implementation puts the samples, as offsets from the pixel's centre.
    glBindFramebuffer(GL_FRAMEBUFFER, msaa_.get());
    GLint n = 0;
    glGetIntegerv(GL_SAMPLES, &n);
    resolve_samples_ = std::clamp(n, 1, 8);
    sample_offsets_.assign(16, 0.0f);
    for (int s = 0; s < resolve_samples_ && n > 1; ++s) {
        float position[2] = {0.5f, 0.5f};
        glGetMultisamplefv(GL_SAMPLE_POSITION, GLuint(s), position);
        sample_offsets_[std::size_t(2 * s)] = position[0] - 0.5f;
        sample_offsets_[std::size_t(2 * s + 1)] = position[1] - 0.5f;
    }
}

void RenderTargets::bind_for_drawing() const
{
    glBindFramebuffer(GL_FRAMEBUFFER, msaa_.get());
    glViewport(0, 0, width_, height_);
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT);
}

void RenderTargets::resolve(float near_plane, float far_plane)
{
    glBlitNamedFramebuffer(msaa_.get(), resolved_.get(), 0, 0, width_, height_, 0, 0, width_, height_,
                           GL_COLOR_BUFFER_BIT, GL_NEAREST);
    // A blit of depth copies one sample; the pixel's centre comes from all of them.
    const ShaderProgram& p = *depth_resolve_;
    p.set("u_depth", 0);
    p.set("u_samples", resolve_samples_);
    p.set("u_near", near_plane);
    p.set("u_far", far_plane);
    glProgramUniform2fv(p.id(), p.location("u_offsets"), 8, sample_offsets_.data());
    p.use();
    glBindFramebuffer(GL_FRAMEBUFFER, resolved_.get());
    glViewport(0, 0, width_, height_);
    glBindTextureUnit(0, msaa_depth_.get());
    glDisable(GL_BLEND);
    draw_fullscreen_depth(empty_vao_.get());
}

std::vector<std::uint8_t> RenderTargets::read_rgba() const
{
    const std::size_t row = std::size_t(width_) * 4;
    std::vector<std::uint8_t> rgba(row * height_);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, display_.get());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    flip_rows(rgba, row);
    return rgba;
}

std::vector<float> RenderTargets::read_samples() const
{
    const int n = std::max(resolve_samples_, 1);
    std::vector<float> rgba(std::size_t(width_) * std::size_t(n) * std::size_t(height_) * 4);
    if (rgba.empty())
        return rgba;
    if (!copy_samples_)
        copy_samples_ = std::make_shared<ShaderProgram>(std::initializer_list<std::string_view>{"copy_samples.comp"});
    Texture side_by_side = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(side_by_side.get(), 1, GL_RGBA32F, width_ * n, height_);
    const ShaderProgram& p = *copy_samples_;
    p.set("u_color", 0);
    p.set("u_samples", n);
    p.set("u_size", glm::ivec2(width_, height_));
    p.use();
    glBindTextureUnit(0, msaa_color_.get());
    glBindImageTexture(0, side_by_side.get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glDispatchCompute(GLuint((width_ + 7) / 8), GLuint((height_ + 7) / 8), 1);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(side_by_side.get(), 0, GL_RGBA, GL_FLOAT, GLsizei(rgba.size() * sizeof(float)), rgba.data());
    flip_rows(rgba, std::size_t(width_) * std::size_t(n) * 4);
    return rgba;
}

float RenderTargets::read_depth(int x, int y) const
{
    float depth = 1.0f;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, resolved_.get());
    glReadPixels(x, height_ - 1 - y, 1, 1, GL_DEPTH_COMPONENT, GL_FLOAT, &depth);
    return depth;
}

}  // namespace kiri::render::detail
