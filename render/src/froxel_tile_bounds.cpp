#include "froxel_tile_bounds.hpp"

#include <glm/matrix.hpp>

#include <algorithm>

namespace kiri::render::detail {
namespace {

constexpr float relative_pad = 0.01f;  // fog-aware ranges grow by 1 % each way

void nearest(GLuint texture)
{
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

}  // namespace

FroxelTileBounds::FroxelTileBounds()
    : shell_program_({"froxel_shell.vert", "froxel_shell.frag"}),
      reduce_({"view_depth.glsl", "fog_partition.glsl", "froxel_tiles.comp"})
{}

void FroxelTileBounds::set_shell(const ShellMesh& shell)
{
    index_count_ = GLsizei(shell.indices.size());
    if (index_count_ == 0)
        return;
    vao_ = make_vertex_array();
    vertices_ = make_buffer();
    indices_ = make_buffer();
    glNamedBufferStorage(vertices_.get(), GLsizeiptr(shell.positions.size() * sizeof(float)), shell.positions.data(),
                         0);
    glNamedBufferStorage(indices_.get(), GLsizeiptr(shell.indices.size() * sizeof(std::uint32_t)), shell.indices.data(),
                         0);
    glVertexArrayVertexBuffer(vao_.get(), 0, vertices_.get(), 0, 3 * sizeof(float));
    glVertexArrayElementBuffer(vao_.get(), indices_.get());
    glEnableVertexArrayAttrib(vao_.get(), 0);
    glVertexArrayAttribFormat(vao_.get(), 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao_.get(), 0, 0);
}

void FroxelTileBounds::ensure_raster(const glm::ivec2& size)
{
    if (size == raster_ && fbo_)
        return;
    depths_ = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(depths_.get(), 1, GL_RG32F, size.x, size.y);
    nearest(depths_.get());
    fbo_ = make_framebuffer();
    glNamedFramebufferTexture(fbo_.get(), GL_COLOR_ATTACHMENT0, depths_.get(), 0);
    glNamedFramebufferDrawBuffer(fbo_.get(), GL_COLOR_ATTACHMENT0);
    raster_ = size;
}

void FroxelTileBounds::rasterise(const FrameContext& frame, Mode mode, bool shell)
{
    ensure_raster({frame.width, frame.height});
    const float none[4] = {-3e38f, 0.0f, 0.0f, 0.0f};
    glClearNamedFramebufferfv(fbo_.get(), GL_COLOR, 0, none);
    if ((shell || mode == Mode::shell) && index_count_ > 0) {
        // The shell's nearest and farthest depth per pixel, behind the ground or not.
        glBindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
        glViewport(0, 0, raster_.x, raster_.y);
        glDisable(GL_DEPTH_TEST);
        glDepthMask(GL_FALSE);
        glDisable(GL_CULL_FACE);
        glEnablei(GL_BLEND, 0);
        glBlendEquationi(0, GL_MAX);
        const glm::dvec3 forward(-frame.view[0][2], -frame.view[1][2], -frame.view[2][2]);
        shell_program_.set("u_view_projection", frame.view_projection);
        shell_program_.set("u_eye", frame.eye);
        shell_program_.set("u_forward", glm::vec3(forward));
        shell_program_.use();
        glBindVertexArray(vao_.get());
        glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
        glBlendEquationi(0, GL_FUNC_ADD);
        glDisablei(GL_BLEND, 0);
        glDepthMask(GL_TRUE);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
}

void FroxelTileBounds::reduce(const FrameContext& frame, Mode mode, const glm::ivec2& tiles, double near, double far,
                              GLuint depth_texture, GLuint tiles_texture, double haze_top)
{
    const glm::vec2 planes = depth_planes(frame);
    reduce_.set("u_shell_depths", 0);
    reduce_.set("u_ground", 2);
    reduce_.set("u_raster", raster_);
    reduce_.set("u_tiles", tiles);
    reduce_.set("u_near_plane", planes.x);
    reduce_.set("u_far_plane", planes.y);
    reduce_.set("u_near", float(near));
    reduce_.set("u_far", float(far));
    reduce_.set("u_mode", int(mode));
    reduce_.set("u_pad", relative_pad);
    reduce_.set("u_inverse_view_projection", glm::inverse(frame.view_projection));
    reduce_.set("u_eye", frame.eye);
    reduce_.set("u_forward", glm::vec3(-frame.view[0][2], -frame.view[1][2], -frame.view[2][2]));
    reduce_.set("u_haze_top", float(haze_top));
    set_partition_uniforms(reduce_, frame);
    reduce_.use();
    glBindTextureUnit(0, depths_.get());
    glBindTextureUnit(2, depth_texture);
    glBindImageTexture(0, tiles_texture, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glDispatchCompute(GLuint((tiles.x + 7) / 8), GLuint((tiles.y + 7) / 8), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

}  // namespace kiri::render::detail
