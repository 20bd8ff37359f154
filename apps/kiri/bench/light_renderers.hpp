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
    //! scene's options), drawn at `scale` times width x height and box-filtered down: each area's
    //! mean, as the path tracer's pixel is the mean light over it to first order. Empty where the
    //! renderer does not draw the scene's fog (layers and particles draw no height fog).
    std::vector<double> luminance(const std::filesystem::path& scene_file, const std::string& camera,
                                  render::FogMode mode, int width, int height, int scale);

private:
    std::unique_ptr<render::GlContext> context_;
};

}  // namespace kiri::bench
