#pragma once
//! \file gl_context.hpp
//! An OpenGL 4.5 core context: headless (EGL surfaceless, CLI and tests) or a GLFW window
//! (the preview). Renderers draw into their own framebuffers and never care which.
#include <memory>
#include <string>

namespace kiri::render {

class GlContext {
public:
    virtual ~GlContext() = default;
    virtual void make_current() = 0;
    //! "OpenGL 4.5 (Mesa llvmpipe ...)" for logs and reports.
    virtual std::string description() const = 0;
};

struct ContextOptions {
    bool debug = true;               //!< KHR_debug messages routed to the log
    bool throw_on_gl_error = false;  //!< tests: a GL error message throws kiri::Error
};

//! \throw kiri::Error with one clear line when EGL or GL 4.5 core is not available.
std::unique_ptr<GlContext> create_headless_context(const ContextOptions& options = {});

//! Number of GL errors reported through KHR_debug since the context was created.
int gl_error_count();

}  // namespace kiri::render
