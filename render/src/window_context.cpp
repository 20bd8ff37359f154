#include "kiri/render/window_context.hpp"

#include <epoxy/gl.h>
// epoxy must come first: GLFW then skips its own GL header.
#include <GLFW/glfw3.h>

#include <cstring>
#include <vector>

#include "gl_debug.hpp"
#include "kiri/geometry/core/error.hpp"

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
        throw Error("GLFW: cannot open a window (no display? set DISPLAY or run under xvfb-run): " + g_last_glfw_error);
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
    context->description_ = std::string("OpenGL ") + reinterpret_cast<const char*>(glGetString(GL_VERSION)) + " (" +
        reinterpret_cast<const char*>(glGetString(GL_RENDERER)) + ", GLFW window)";
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
void WindowContext::framebuffer_size(int& width, int& height) const
{
    glfwGetFramebufferSize(window_, &width, &height);
}

Image WindowContext::read_back_buffer() const
{
    int w = 0, h = 0;
    framebuffer_size(w, h);
    Image image{w, h, std::vector<std::uint8_t>(std::size_t(w) * h * 4)};
    std::vector<std::uint8_t> bottom_up(image.rgba.size());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
    const std::size_t row = std::size_t(w) * 4;
    for (int y = 0; y < h; ++y)
        std::memcpy(&image.rgba[std::size_t(y) * row], &bottom_up[std::size_t(h - 1 - y) * row], row);
    for (std::size_t i = 3; i < image.rgba.size(); i += 4)
        image.rgba[i] = 255;  // the window has no meaningful alpha
    return image;
}

}  // namespace kiri::render
