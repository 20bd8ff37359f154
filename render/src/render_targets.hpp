#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "gl_objects.hpp"

namespace kiri::render::detail {

class ShaderProgram;

//! A frame's samples before the resolve (RenderTargets::frame_samples): the passes after the resolve
//! that split a pixel whose samples see two surfaces (the froxels' apply, the layers' composite).
struct FrameSamples {
    GLuint color = 0, depth = 0;
    int count = 1;
    const float* offsets = nullptr;  //!< each sample's offset from the pixel's centre (x, y; 8)
};

//! Samples 1..3's blend targets beside colour attachment 0 of `fbo`, for a pass that draws a
//! still along each of a pixel's four samples' rays, each sample's blend apart (layers.frag's
//! LAYERS_AT_SAMPLES, particles.frag's PARTICLES_AT_SAMPLES; sample_blends.glsl puts them over
//! the frame): width x height of `format`, read texel by texel. Without `at_samples`, none, and
//! `fbo` draws into attachment 0 alone.
void attach_sample_blends(GLuint fbo, Texture (&blends)[3], int width, int height, GLenum format, bool at_samples);

//! The offscreen framebuffers of a frame. Passes draw linear radiance into a 4x multisampled
//! half-float target (colour RGBA16F, depth 32F), resolved into single-sampled copies ("hdr")
//! that later passes blend into (layers, fog); the depth is resolved to each pixel's centre
//! (depth_resolve.frag), where those passes take it to lie; one tone-mapping pass turns it into the 8-bit
//! "display" image that is read back or shown, which shares the resolved depth so overlays
//! drawn on it are depth-tested against the scene.
class RenderTargets {
public:
    static constexpr int samples = 4;
    //! (Re)allocates only when the size changes.
    void ensure(int width, int height);
    void bind_for_drawing() const;
    //! The colour averaged, the depth at each pixel's centre (depth_resolve.frag); the near and
    //! far planes of the frame's projection.
    void resolve(float near_plane, float far_plane);
    //! Colour rows top to bottom (the GL origin is bottom-left).
    std::vector<std::uint8_t> read_rgba() const;
    //! Every sample's linear radiance before the resolve (RGBA; rows top to bottom, per pixel its
    //! resolved_samples() samples in turn).
    std::vector<float> read_samples() const;
    //! Depth in [0, 1] of pixel (x, y), origin top-left.
    float read_depth(int x, int y) const;
    //! Resolved linear radiance (+ depth): where passes after the resolve blend.
    GLuint hdr_framebuffer() const { return resolved_.get(); }
    GLuint hdr_color() const { return resolved_color_.get(); }
    GLuint resolved_depth() const { return resolved_depth_.get(); }
    //! How many samples a pixel has.
    int resolved_samples() const { return resolve_samples_; }
    //! Each sample's offset from its pixel's centre (pixels; x, y per sample, 8 samples).
    const float* sample_offsets() const { return sample_offsets_.data(); }
    //! The multisampled colour and depth before the resolve, for the passes after it that split a
    //! pixel whose samples see two surfaces.
    FrameSamples frame_samples() const
    {
        return {msaa_color_.get(), msaa_depth_.get(), resolve_samples_, sample_offsets_.data()};
    }
    //! The tone-mapped 8-bit image (+ the resolved depth).
    GLuint display_framebuffer() const { return display_.get(); }
    int width() const { return width_; }
    int height() const { return height_; }

private:
    void prepare_depth_resolve();
    int width_ = 0, height_ = 0;
    Framebuffer msaa_, resolved_, display_;
    Renderbuffer display_color_;
    Texture msaa_color_, msaa_depth_;          // multisampled, read by the resolve and the froxels' edges
    Texture resolved_color_, resolved_depth_;  // sampled by passes drawn after the resolve
    std::shared_ptr<ShaderProgram> depth_resolve_;
    mutable std::shared_ptr<ShaderProgram> copy_samples_;  // built on first use
    VertexArray empty_vao_;
    int resolve_samples_ = 0;
    std::vector<float> sample_offsets_;  // depth_resolve.frag's u_offsets
};

}  // namespace kiri::render::detail
