#include "froxel_tile_bounds.hpp"

#include <algorithm>

#include "terrain_pass.hpp"

namespace kiri::render::detail {
namespace {

constexpr int samples_per_tile = 4;  // raster samples per tile side
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
    : shell_program_({"froxel_shell.vert", "froxel_shell.frag"}), depth_program_({"terrain.vert", "depth_only.frag"}),
      reduce_({"froxel_tiles.comp"})
{
}

void FroxelTileBounds::set_shell(const ShellMesh& shell)
{
    index_count_ = GLsizei(shell.indices.size());
    if (index_count_ == 0)
        return;
    vao_ = make_vertex_array();
    vertices_ = make_buffer();
    indices_ = make_buffer();
    glNamedBufferStorage(vertices_.get(), GLsizeiptr(shell.positions.size() * sizeof(float)), shell.positions.data(), 0);
    glNamedBufferStorage(indices_.get(), GLsizeiptr(shell.indices.size() * sizeof(std::uint32_t)), shell.indices.data(), 0);
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
    first_ = make_texture(GL_TEXTURE_2D);
    last_ = make_texture(GL_TEXTURE_2D);
    ground_ = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(first_.get(), 1, GL_R32F, size.x, size.y);
    glTextureStorage2D(last_.get(), 1, GL_R32F, size.x, size.y);
    glTextureStorage2D(ground_.get(), 1, GL_DEPTH_COMPONENT32F, size.x, size.y);
    for (GLuint t : {first_.get(), last_.get(), ground_.get()})
        nearest(t);
    fbo_ = make_framebuffer();
    glNamedFramebufferTexture(fbo_.get(), GL_COLOR_ATTACHMENT0, first_.get(), 0);
    glNamedFramebufferTexture(fbo_.get(), GL_COLOR_ATTACHMENT1, last_.get(), 0);
    glNamedFramebufferTexture(fbo_.get(), GL_DEPTH_ATTACHMENT, ground_.get(), 0);
    raster_ = size;
}

void FroxelTileBounds::update(const FrameContext& frame, const TerrainPass& terrain, Mode mode,
                              const glm::ivec2& tiles, double near, double far, GLuint tiles_texture)
{
    {  // the ground in every mode (the apply weighs tiles by it); the shell when fog-aware
        const glm::ivec2 size = glm::min(tiles * samples_per_tile, glm::ivec2(frame.width, frame.height));
        ensure_raster(glm::max(size, glm::ivec2(1)));
        glBindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
        glViewport(0, 0, raster_.x, raster_.y);
        // The ground's depth (sky: the far plane).
        const GLenum none = GL_NONE;
        glNamedFramebufferDrawBuffers(fbo_.get(), 1, &none);
        const float far_depth = 1.0f;
        glClearNamedFramebufferfv(fbo_.get(), GL_DEPTH, 0, &far_depth);  // sky: the far plane
        depth_program_.set("u_view_projection", frame.view_projection);
        depth_program_.use();
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glDisable(GL_CULL_FACE);
        terrain.draw_mesh();
        // The shell's nearest and farthest depth per sample, behind the ground or not.
        const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
        glNamedFramebufferDrawBuffers(fbo_.get(), 2, both);
        const float none_first[4] = {3e38f, 0.0f, 0.0f, 0.0f}, none_last[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        glClearNamedFramebufferfv(fbo_.get(), GL_COLOR, 0, none_first);
        glClearNamedFramebufferfv(fbo_.get(), GL_COLOR, 1, none_last);
        if (mode == Mode::shell && index_count_ > 0) {
            glDisable(GL_DEPTH_TEST);
            glDepthMask(GL_FALSE);
            glEnablei(GL_BLEND, 0);
            glEnablei(GL_BLEND, 1);
            glBlendEquationi(0, GL_MIN);
            glBlendEquationi(1, GL_MAX);
            const glm::dvec3 forward(-frame.view[0][2], -frame.view[1][2], -frame.view[2][2]);
            shell_program_.set("u_view_projection", frame.view_projection);
            shell_program_.set("u_eye", frame.eye);
            shell_program_.set("u_forward", glm::vec3(forward));
            shell_program_.use();
            glBindVertexArray(vao_.get());
            glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
            glBlendEquationi(0, GL_FUNC_ADD);
            glBlendEquationi(1, GL_FUNC_ADD);
            glDisablei(GL_BLEND, 0);
            glDisablei(GL_BLEND, 1);
            glDepthMask(GL_TRUE);
        }
        glNamedFramebufferDrawBuffers(fbo_.get(), 2, both);
    }
    // The ground on each tile's central ray: a depth raster with one pixel per tile.
    if (tiles != tiles_ || !centres_fbo_) {
        centres_ = make_texture(GL_TEXTURE_2D);
        glTextureStorage2D(centres_.get(), 1, GL_DEPTH_COMPONENT32F, tiles.x, tiles.y);
        nearest(centres_.get());
        centres_fbo_ = make_framebuffer();
        glNamedFramebufferTexture(centres_fbo_.get(), GL_DEPTH_ATTACHMENT, centres_.get(), 0);
        glNamedFramebufferDrawBuffer(centres_fbo_.get(), GL_NONE);
        tiles_ = tiles;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, centres_fbo_.get());
    glViewport(0, 0, tiles.x, tiles.y);
    const float far_depth = 1.0f;
    glClearNamedFramebufferfv(centres_fbo_.get(), GL_DEPTH, 0, &far_depth);
    depth_program_.set("u_view_projection", frame.view_projection);
    depth_program_.use();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    terrain.draw_mesh();

    const double p22 = frame.projection[2][2], p32 = frame.projection[3][2];
    reduce_.set("u_centres", 3);
    reduce_.set("u_first", 0);
    reduce_.set("u_last", 1);
    reduce_.set("u_ground", 2);
    reduce_.set("u_raster", raster_);
    reduce_.set("u_tiles", tiles);
    reduce_.set("u_near_plane", float(p32 / (p22 - 1.0)));
    reduce_.set("u_far_plane", float(p32 / (p22 + 1.0)));
    reduce_.set("u_near", float(near));
    reduce_.set("u_far", float(far));
    reduce_.set("u_mode", int(mode));
    reduce_.set("u_pad", relative_pad);
    reduce_.use();
    {
        glBindTextureUnit(0, first_.get());
        glBindTextureUnit(1, last_.get());
        glBindTextureUnit(2, ground_.get());
        glBindTextureUnit(3, centres_.get());
    }
    glBindImageTexture(0, tiles_texture, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glDispatchCompute(GLuint((tiles.x + 7) / 8), GLuint((tiles.y + 7) / 8), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

}  // namespace kiri::render::detail
