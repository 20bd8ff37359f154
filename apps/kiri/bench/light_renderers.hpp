#pragma once
// The light bench's GL side: each renderer's picture of a view's fog under the baked lighting
// model, over a black world (no sky, a black ground), as luminance at the path tracer's size.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "kiri/render/gl_context.hpp"
#include "kiri/render/renderer.hpp"

namespace kiri::bench {

class LightFrames {
public:
    LightFrames();
    //! `scene_file` from `camera` in `mode` with multiple_scattering baked (the bake at the
    //! scene's options), drawn at `scale` times width x height; each pixel of the result is the
    //! mean of the frame's pixels at its centre (2x2 of them for an even scale), where the path
    //! tracer's one ray a pixel runs: a pixel that holds a fog edge is judged by the light near
    //! that ray, not by the fog's share of the pixel. Empty where the renderer does not draw the
    //! scene's fog (layers and particles draw no height fog).
    std::vector<double> luminance(const std::filesystem::path& scene_file, const std::string& camera,
                                  render::FogMode mode, int width, int height, int scale);

private:
    std::unique_ptr<render::GlContext> context_;
};

}  // namespace kiri::bench
