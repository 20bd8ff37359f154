#pragma once
// RAII owners of GL object names. Move-only; a moved-from owner holds 0.
#include <epoxy/gl.h>

#include <utility>

namespace kiri::render::detail {

template <void (*Delete)(GLuint)>
class GlName {
public:
    GlName() = default;
    explicit GlName(GLuint name) : name_(name) {}
    ~GlName() { reset(); }
    GlName(GlName&& other) noexcept : name_(std::exchange(other.name_, 0)) {}
    GlName& operator=(GlName&& other) noexcept
    {
        if (this != &other) {
            reset();
            name_ = std::exchange(other.name_, 0);
        }
        return *this;
    }
    GlName(const GlName&) = delete;
    GlName& operator=(const GlName&) = delete;

    GLuint get() const { return name_; }
    explicit operator bool() const { return name_ != 0; }
    void reset()
    {
        if (name_)
            Delete(name_);
        name_ = 0;
    }

private:
    GLuint name_ = 0;
};

inline void delete_buffer(GLuint n) { glDeleteBuffers(1, &n); }
inline void delete_vertex_array(GLuint n) { glDeleteVertexArrays(1, &n); }
inline void delete_texture(GLuint n) { glDeleteTextures(1, &n); }
inline void delete_framebuffer(GLuint n) { glDeleteFramebuffers(1, &n); }
inline void delete_renderbuffer(GLuint n) { glDeleteRenderbuffers(1, &n); }
inline void delete_query(GLuint n) { glDeleteQueries(1, &n); }
inline void delete_program(GLuint n) { glDeleteProgram(n); }

using Buffer = GlName<delete_buffer>;
using VertexArray = GlName<delete_vertex_array>;
using Texture = GlName<delete_texture>;
using Framebuffer = GlName<delete_framebuffer>;
using Renderbuffer = GlName<delete_renderbuffer>;
using Query = GlName<delete_query>;
using ProgramName = GlName<delete_program>;

inline Buffer make_buffer()
{
    GLuint n = 0;
    glCreateBuffers(1, &n);
    return Buffer(n);
}
inline VertexArray make_vertex_array()
{
    GLuint n = 0;
    glCreateVertexArrays(1, &n);
    return VertexArray(n);
}
inline Texture make_texture(GLenum target)
{
    GLuint n = 0;
    glCreateTextures(target, 1, &n);
    return Texture(n);
}
inline Framebuffer make_framebuffer()
{
    GLuint n = 0;
    glCreateFramebuffers(1, &n);
    return Framebuffer(n);
}
inline Renderbuffer make_renderbuffer()
{
    GLuint n = 0;
    glCreateRenderbuffers(1, &n);
    return Renderbuffer(n);
}
inline Query make_query(GLenum target)
{
    GLuint n = 0;
    glCreateQueries(target, 1, &n);
    return Query(n);
}

}  // namespace kiri::render::detail
