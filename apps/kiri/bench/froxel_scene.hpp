#pragma once
// The froxel fog's benchmark scene: the bundled fog lake over Jacksboro from its first camera,
// the CPU reference of it, and froxel frames measured against it.
#include <filesystem>
#include <memory>

#include "kiri/geometry/volume/froxel_options.hpp"
#include "kiri/geometry/reference/reference_fog.hpp"
#include "kiri/geometry/scene/scene.hpp"
#include "kiri/geometry/scene/pipeline.hpp"
#include "kiri/geometry/terrain/terrain.hpp"
#include "kiri/render/camera.hpp"
#include "kiri/render/fog_error.hpp"
#include "kiri/render/gl_context.hpp"
#include "kiri/render/image.hpp"
#include "kiri/render/renderer.hpp"

namespace kiri::bench {

struct FroxelBenchScene {
    geometry::Scene scene;
    geometry::PipelineProducts products;  //!< the scene's fog up to its Medium
    const geometry::Terrain& terrain;
    geometry::Medium medium;  //!< the products' Medium, its time nudged by frame_seconds
    std::unique_ptr<render::GlContext> context;
    std::unique_ptr<render::Renderer> renderer;
    render::Camera camera;

    explicit FroxelBenchScene(const std::filesystem::path& scene_file);
    //! The scene's froxel options, temporal filtering off (one frame is one measurement), the
    //! volume's far end fixed so that the reference stops at the same depth.
    geometry::FroxelOptions options() const;
    geometry::FogLighting lighting(const geometry::FroxelOptions& options) const;
    geometry::ReferenceView view(int width, int height, const geometry::FroxelOptions& options) const;
    //! Median wall time of `frames` froxel frames with every pass rerun (the fog's time nudged).
    double frame_seconds(const geometry::FroxelOptions& options, const render::Camera& camera, int width, int height,
                         int frames);
    //! The fog of one frame against the reference.
    render::FogError error(const geometry::FroxelOptions& options, const geometry::ReferenceImage& reference);
};

}  // namespace kiri::bench
