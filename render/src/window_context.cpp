#include "kiri/render/window_context.hpp"

#include <epoxy/gl.h>
// epoxy must come first: GLFW then skips its own GL header.
#include <GLFW/glfw3.h>

#include "gl_debug.hpp"
#include "kiri/geometry/error.hpp"

namespace kiri::render {
namespace {
std::string g_last_glfw_error;
void on_glfw_error(int, const char* message) { g_last_glfw_error = message ? message : ""; }
}  // namespace

std::unique_ptr<WindowContext> create_window_context(int width, int height, const std::string& title,
                                                     const ContextOptions& options)
{
    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit())
        throw Error("GLFW: cannot open a window (no display? set DISPLAY or run under xvfb-run): " +
                    g_last_glfw_error);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, options.debug ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE);
    std::unique_ptr<WindowContext> context(new WindowContext());
    context->window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!context->window_) {
        const std::string reason = g_last_glfw_error;
        glfwTerminate();
        throw Error("GLFW: cannot create an OpenGL 4.5 core window: " + reason);
    }
    context->make_current();
    glfwSwapInterval(1);
    context->description_ = std::string("OpenGL ") + reinterpret_cast<const char*>(glGetString(GL_VERSION)) +
                            " (" + reinterpret_cast<const char*>(glGetString(GL_RENDERER)) + ", GLFW window)";
    if (options.debug || options.throw_on_gl_error)
        detail::install_debug_callback(options.throw_on_gl_error);
    return context;
}

WindowContext::~WindowContext()
{
    if (window_)
        glfwDestroyWindow(window_);
    glfwTerminate();
}

void WindowContext::make_current() { glfwMakeContextCurrent(window_); }
std::string WindowContext::description() const { return description_; }
bool WindowContext::should_close() const { return glfwWindowShouldClose(window_); }
void WindowContext::swap_buffers() { glfwSwapBuffers(window_); }
void WindowContext::framebuffer_size(int& width, int& height) const { glfwGetFramebufferSize(window_, &width, &height); }

}  // namespace kiri::render
