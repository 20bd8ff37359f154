#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <cstring>
#include <string>

#include "gl_debug.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/render/gl_context.hpp"

namespace kiri::render {
namespace {

bool has_extension(const char* list, const char* name)
{
    if (!list)
        return false;
    const std::size_t n = std::strlen(name);
    for (const char* p = std::strstr(list, name); p; p = std::strstr(p + n, name))
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0'))
            return true;
    return false;
}

// Surfaceless Mesa: no window system and no EGL config; everything draws into FBOs.
class EglContext final : public GlContext {
public:
    explicit EglContext(const ContextOptions& options)
    {
        const char* client_ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
        if (!has_extension(client_ext, "EGL_MESA_platform_surfaceless"))
            throw Error(
                "EGL: the surfaceless platform (EGL_MESA_platform_surfaceless) is not available; "
                "install libegl-mesa0 and libgl1-mesa-dri");
        display_ = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        EGLint major = 0, minor = 0;
        if (display_ == EGL_NO_DISPLAY || !eglInitialize(display_, &major, &minor))
            throw Error("EGL: cannot initialise the surfaceless display");
        if (!has_extension(eglQueryString(display_, EGL_EXTENSIONS), "EGL_KHR_no_config_context"))
            throw Error("EGL: EGL_KHR_no_config_context is missing, cannot create a headless context");
        if (!eglBindAPI(EGL_OPENGL_API))
            throw Error("EGL: desktop OpenGL is not available");
        const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                     4,
                                     EGL_CONTEXT_MINOR_VERSION,
                                     5,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                     EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_CONTEXT_OPENGL_DEBUG,
                                     options.debug ? EGL_TRUE : EGL_FALSE,
                                     EGL_NONE};
        context_ = eglCreateContext(display_, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
        if (context_ == EGL_NO_CONTEXT) {
            eglTerminate(display_);
            throw Error("EGL: cannot create an OpenGL 4.5 core context (the driver offers less)");
        }
        make_current();
        if (epoxy_gl_version() < 45) {
            release();
            throw Error("EGL: OpenGL 4.5 core is required");
        }
        description_ = std::string("OpenGL ") + reinterpret_cast<const char*>(glGetString(GL_VERSION)) + " (" +
            reinterpret_cast<const char*>(glGetString(GL_RENDERER)) + ", EGL surfaceless)";
        if (options.debug || options.throw_on_gl_error)
            detail::install_debug_callback(options.throw_on_gl_error);
    }

    ~EglContext() override { release(); }

    void make_current() override
    {
        if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
            throw Error("EGL: cannot make the context current");
    }

    std::string description() const override { return description_; }

private:
    void release()
    {
        if (display_ == EGL_NO_DISPLAY)
            return;
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (context_ != EGL_NO_CONTEXT)
            eglDestroyContext(display_, context_);
        eglTerminate(display_);
        display_ = EGL_NO_DISPLAY;
    }

    EGLDisplay display_ = EGL_NO_DISPLAY;
    EGLContext context_ = EGL_NO_CONTEXT;
    std::string description_;
};

}  // namespace

std::unique_ptr<GlContext> create_headless_context(const ContextOptions& options)
{
    return std::make_unique<EglContext>(options);
}

}  // namespace kiri::render
