#pragma once
//! \file window_context.hpp
//! A GLFW window with an OpenGL 4.5 core context, for the interactive preview.
#include <memory>
#include <string>

#include "kiri/render/gl_context.hpp"
#include "kiri/render/image.hpp"

struct GLFWwindow;

namespace kiri::render {

class WindowContext : public GlContext {
public:
    ~WindowContext() override;
    void make_current() override;
    std::string description() const override;
    GLFWwindow* window() const { return window_; }
    bool should_close() const;
    void swap_buffers();
    //! Framebuffer size in pixels (differs from the window size on HiDPI screens).
    void framebuffer_size(int& width, int& height) const;
    //! The back buffer as drawn so far this frame (scene and panel), rows top to bottom.
    Image read_back_buffer() const;

private:
    friend std::unique_ptr<WindowContext> create_window_context(int, int, const std::string&, const ContextOptions&);
    WindowContext() = default;
    GLFWwindow* window_ = nullptr;
    std::string description_;
};

//! \throw kiri::Error with one clear line when there is no display or no OpenGL 4.5.
std::unique_ptr<WindowContext> create_window_context(int width, int height, const std::string& title,
                                                     const ContextOptions& options = {});

}  // namespace kiri::render
