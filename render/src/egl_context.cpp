#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

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

// A headless display: Mesa's surfaceless platform where it is (llvmpipe, CI), else a GPU found
// through EGL_EXT_platform_device (NVIDIA's driver has no surfaceless platform). The
// environment variable KIRI_EGL_PLATFORM=surfaceless or device forces one.
struct HeadlessDisplay {
    EGLDisplay display = EGL_NO_DISPLAY;
    const char* platform = "";
};

bool initialise(EGLDisplay display)
{
    EGLint major = 0, minor = 0;
    return display != EGL_NO_DISPLAY && eglInitialize(display, &major, &minor);
}

HeadlessDisplay surfaceless_display()
{
    const EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (!initialise(display))
        throw Error("EGL: cannot initialise the surfaceless display");
    return {display, "EGL surfaceless"};
}

// The first device that initialises, hardware before software (Mesa lists llvmpipe as a device
// with EGL_MESA_device_software).
HeadlessDisplay device_display()
{
    EGLint count = 0;
    if (!eglQueryDevicesEXT(0, nullptr, &count) || count <= 0)
        throw Error("EGL: no EGL device found (EGL_EXT_platform_device lists none)");
    std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
    eglQueryDevicesEXT(count, devices.data(), &count);
    for (const bool software : {false, true})
        for (EGLint i = 0; i < count; ++i) {
            const char* extensions = eglQueryDeviceStringEXT(devices[i], EGL_EXTENSIONS);
            if (has_extension(extensions, "EGL_MESA_device_software") != software)
                continue;
            const EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
            if (initialise(display))
                return {display, software ? "EGL device, software" : "EGL device"};
        }
    throw Error("EGL: none of the " + std::to_string(count) + " EGL devices could be initialised");
}

HeadlessDisplay headless_display()
{
    const char* client_ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    const bool surfaceless = has_extension(client_ext, "EGL_MESA_platform_surfaceless");
    const bool device = has_extension(client_ext, "EGL_EXT_platform_device") &&
        (has_extension(client_ext, "EGL_EXT_device_enumeration") || has_extension(client_ext, "EGL_EXT_device_base"));
    const char* forced = std::getenv("KIRI_EGL_PLATFORM");
    const std::string want = forced ? forced : "";
    if (!want.empty() && want != "surfaceless" && want != "device")
        throw Error("KIRI_EGL_PLATFORM: '" + want + "' is neither 'surfaceless' nor 'device'");
    if (want == "surfaceless" || (want.empty() && surfaceless)) {
        if (!surfaceless)
            throw Error("EGL: the surfaceless platform (EGL_MESA_platform_surfaceless) is not available");
        return surfaceless_display();
    }
    if (!device)
        throw Error(
            "EGL: neither the surfaceless platform (EGL_MESA_platform_surfaceless) nor EGL devices "
            "(EGL_EXT_platform_device) are available; install libegl-mesa0 and libgl1-mesa-dri");
    return device_display();
}

// No window system: everything draws into FBOs. Without EGL_KHR_no_config_context (some
// drivers) the context takes a pbuffer-capable config and is still made current with no surface.
class EglContext final : public GlContext {
public:
    explicit EglContext(const ContextOptions& options)
    {
        const HeadlessDisplay headless = headless_display();
        display_ = headless.display;
        EGLConfig config = EGL_NO_CONFIG_KHR;
        const char* display_ext = eglQueryString(display_, EGL_EXTENSIONS);
        if (!has_extension(display_ext, "EGL_KHR_surfaceless_context")) {
            eglTerminate(display_);
            throw Error("EGL: EGL_KHR_surfaceless_context is missing, cannot draw without a surface");
        }
        if (!has_extension(display_ext, "EGL_KHR_no_config_context")) {
            const EGLint wanted[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_NONE};
            EGLint found = 0;
            if (!eglChooseConfig(display_, wanted, &config, 1, &found) || found < 1) {
                eglTerminate(display_);
                throw Error("EGL: no config for desktop OpenGL, cannot create a headless context");
            }
        }
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
        context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, attributes);
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
            reinterpret_cast<const char*>(glGetString(GL_RENDERER)) + ", " + headless.platform + ")";
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
    // A debug context validates every call, which some drivers pay for in time (timing runs
    // on a GPU set KIRI_GL_DEBUG=0); a test that throws on GL errors keeps its callback.
    ContextOptions chosen = options;
    if (const char* debug = std::getenv("KIRI_GL_DEBUG"); debug && std::string(debug) == "0")
        chosen.debug = false;
    return std::make_unique<EglContext>(chosen);
}

}  // namespace kiri::render
