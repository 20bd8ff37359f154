#pragma once
// The scene of the layer benchmarks: a 3 x 3 km fog (1000 m patches, like the source's few
// patches) over the middle of Jacksboro, and views of it for the figures and Table 3.2.
#include <filesystem>
#include <memory>

#include "kiri/geometry/scene/scene.hpp"
#include "kiri/geometry/scene/pipeline.hpp"
#include "kiri/geometry/terrain/terrain.hpp"
#include "kiri/render/camera.hpp"
#include "kiri/render/gl_context.hpp"
#include "kiri/render/renderer.hpp"

namespace kiri::bench {

//! A layer stack to draw: its base and its options (world units).
struct LayerFog {
    std::shared_ptr<const geometry::LayerBase> base;
    geometry::LayerOptions layers;
};

struct LayerBenchScene {
    geometry::Scene scene;
    geometry::Pipeline pipeline;  //!< keeps the terrain and redoes only what each fog changes
    const geometry::Terrain& terrain;
    std::unique_ptr<render::GlContext> context;
    std::unique_ptr<render::Renderer> renderer;

    explicit LayerBenchScene(const std::filesystem::path& data_dir);
    //! The fog at tessellation `level` with `count` layers (options applied on top).
    LayerFog fog(int level, int count, double fade_width = 0.5);
    //! Oblique view, the stack filling about two thirds of a 16:9 frame.
    render::Camera oblique() const;
    render::Camera side_near() const;
    render::Camera top() const;
    //! Looking away from the fog (it is off-screen).
    render::Camera away() const;
    //! Median frame time (s) of `frames` draws after two warm-up frames.
    double frame_seconds(const render::Camera& camera, int width, int height, int frames);
};

//! Mean |a - b| over the RGB channels, in 8-bit levels.
double mean_abs_difference(const render::Image& a, const render::Image& b);
//! Share of pixels differing by more than 2 levels in some channel.
double changed_fraction(const render::Image& a, const render::Image& b);

}  // namespace kiri::bench
