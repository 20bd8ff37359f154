#include "gl_debug.hpp"

#include <epoxy/gl.h>

#include <atomic>
#include <cstdio>

#include "kiri/geometry/core/error.hpp"
#include "kiri/render/gl_context.hpp"

namespace kiri::render {
namespace {
std::atomic<int> g_error_count{0};
std::atomic<int> g_checked_count{0};
bool g_throw_on_error = false;

const char* type_name(GLenum type)
{
    switch (type) {
    case GL_DEBUG_TYPE_ERROR: return "error";
    case GL_DEBUG_TYPE_DEPRECATED_BEHAVIOR: return "deprecated";
    case GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR: return "undefined behaviour";
    case GL_DEBUG_TYPE_PORTABILITY: return "portability";
    case GL_DEBUG_TYPE_PERFORMANCE: return "performance";
    default: return "other";
    }
}

void GLAPIENTRY on_message(GLenum /*source*/, GLenum type, GLuint /*id*/, GLenum severity, GLsizei /*length*/,
                           const GLchar* message, const void* /*user*/)
{
    if (type == GL_DEBUG_TYPE_ERROR)
        ++g_error_count;
    // Notifications (buffer placement hints and the like) are noise for users.
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION)
        return;
    if (severity == GL_DEBUG_SEVERITY_LOW && type != GL_DEBUG_TYPE_ERROR)
        return;
    std::fprintf(stderr, "kiri gl: %s: %s\n", type_name(type), message);
}
}  // namespace

int gl_error_count() { return g_error_count.load(); }

namespace detail {

void install_debug_callback(bool throw_on_error)
{
    g_throw_on_error = throw_on_error;
    if (!epoxy_has_gl_extension("GL_KHR_debug") && epoxy_gl_version() < 43)
        return;
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(on_message, nullptr);
}

void check_gl_errors(const char* where)
{
    const int now = g_error_count.load();
    const int before = g_checked_count.exchange(now);
    if (g_throw_on_error && now != before)
        throw Error(std::string("OpenGL reported ") + std::to_string(now - before) + " error(s) during " + where);
}

}  // namespace detail
}  // namespace kiri::render
