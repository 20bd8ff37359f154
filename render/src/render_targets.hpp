#pragma once
#include <cstdint>
#include <vector>

#include "gl_objects.hpp"

namespace kiri::render::detail {

//! The offscreen framebuffers of a frame: 4x multisampled colour (RGBA8) and depth (32F),
//! resolved into single-sampled copies that are read back.
class RenderTargets {
public:
    static constexpr int samples = 4;
    //! (Re)allocates only when the size changes.
    void ensure(int width, int height);
    void bind_for_drawing() const;
    void resolve() const;
    //! Colour rows top to bottom (the GL origin is bottom-left).
    std::vector<std::uint8_t> read_rgba() const;
    //! Depth in [0, 1] of pixel (x, y), origin top-left.
    float read_depth(int x, int y) const;
    GLuint resolved_framebuffer() const { return resolved_.get(); }
    GLuint resolved_depth() const { return resolved_depth_.get(); }
    int width() const { return width_; }
    int height() const { return height_; }

private:
    int width_ = 0, height_ = 0;
    Framebuffer msaa_, resolved_;
    Renderbuffer msaa_color_, msaa_depth_, resolved_color_;
    Texture resolved_depth_;  // sampled by passes drawn after the resolve
};

}  // namespace kiri::render::detail
