// The headless context on each EGL platform kiri knows: Mesa's surfaceless platform (llvmpipe,
// CI) and an EGL device (EGL_EXT_platform_device, what a GPU driver without the surfaceless
// platform offers; Mesa lists llvmpipe as a software device). Each test runs in its own process,
// so the environment variable that picks the platform is read afresh.
#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <cstdlib>
#include <string>

#include "kiri/geometry/core/error.hpp"
#include "kiri/render/camera.hpp"
#include "kiri/render/gl_context.hpp"
#include "kiri/render/renderer.hpp"
#include "render/render_fixture.hpp"

namespace {

using kiri::render::create_headless_context;

kiri::render::Image draw_hill()
{
    const kiri::geometry::Terrain hill = kiri::test::gaussian_hill();
    kiri::render::Renderer renderer;
    renderer.set_terrain(hill);
    kiri::render::Camera camera;
    camera.position = {-300.0, -1500.0, 900.0};
    camera.target = {0.0, 0.0, 80.0};
    return renderer.render(camera, 96, 64);
}

TEST(EglContext, AnEglDeviceDrawsWhatTheSurfacelessPlatformDraws)
{
    kiri::render::Image surfaceless, device;
    {
        setenv("KIRI_EGL_PLATFORM", "surfaceless", 1);
        const auto context = create_headless_context({.debug = true, .throw_on_gl_error = true});
        EXPECT_NE(context->description().find("EGL surfaceless"), std::string::npos) << context->description();
        surfaceless = draw_hill();
    }
    {
        setenv("KIRI_EGL_PLATFORM", "device", 1);
        const auto context = create_headless_context({.debug = true, .throw_on_gl_error = true});
        EXPECT_NE(context->description().find("EGL device"), std::string::npos) << context->description();
        device = draw_hill();
    }
    unsetenv("KIRI_EGL_PLATFORM");
    ASSERT_EQ(device.rgba.size(), surfaceless.rgba.size());
    // The same driver behind both: the same bytes, and a hill, not a cleared target.
    EXPECT_TRUE(device.rgba == surfaceless.rgba);
    std::size_t differing = 0;
    for (std::size_t k = 4; k < device.rgba.size(); ++k)
        differing += device.rgba[k] != device.rgba[k % 4];
    EXPECT_GT(differing, device.rgba.size() / 4);
    EXPECT_EQ(kiri::render::gl_error_count(), 0);
}

TEST(EglContext, AnUnknownPlatformIsOneClearError)
{
    setenv("KIRI_EGL_PLATFORM", "wayland", 1);
    try {
        create_headless_context();
        FAIL() << "a context was made on an unknown platform";
    } catch (const kiri::Error& e) {
        EXPECT_NE(std::string(e.what()).find("KIRI_EGL_PLATFORM: 'wayland'"), std::string::npos) << e.what();
    }
    unsetenv("KIRI_EGL_PLATFORM");
}

TEST(EglContext, KiriGlDebugZeroDropsTheDebugContextButNotATestsErrorCallback)
{
    // A timing run's context (KIRI_GL_DEBUG=0) reports no debug messages; a context whose GL
    // errors must throw keeps its callback and still throws.
    setenv("KIRI_GL_DEBUG", "0", 1);
    const auto context = create_headless_context({.debug = true, .throw_on_gl_error = true});
    unsetenv("KIRI_GL_DEBUG");
    GLint flags = 0;
    glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
    EXPECT_EQ(flags & GL_CONTEXT_FLAG_DEBUG_BIT, 0);
    const int before = kiri::render::gl_error_count();
    glEnable(0xFFFF);  // GL_INVALID_ENUM
    EXPECT_EQ(kiri::render::gl_error_count(), before + 1);
}

}  // namespace
