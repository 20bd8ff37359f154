#pragma once
//! \file scene_rendering.hpp
//! One place that turns a scene and a render mode into what the Renderer draws, so `kiri
//! render`, `kiri bench` and the preview agree: terrain, layers, particles, froxel, or combined
//! (docs/combined.md: every renderer draws its share of the one Medium, froxels near, layers
//! far, particles in the top band, set_fog_partition).
#include <optional>
#include <string_view>

#include "kiri/geometry/medium/fog_lighting.hpp"
#include "kiri/geometry/volume/froxel_options.hpp"
#include "kiri/geometry/particles/particles.hpp"
#include "kiri/geometry/reference/reference_fog.hpp"
#include "kiri/geometry/scene/scene.hpp"
#include "kiri/geometry/scene/scene_fog.hpp"
#include "kiri/render/renderer.hpp"

namespace kiri::render {

enum class FogMode { terrain, layers, particles, froxel, combined };

const char* to_string(FogMode mode);
//! False for any other name.
bool parse_fog_mode(std::string_view name, FogMode& out);

Camera to_camera(const geometry::CameraSpec& camera);
SunLight to_sun(const geometry::SunSpec& sun);
ParticleStyle particle_style(const geometry::ParticleOptions& options);
//! The scene's froxel options in world units, its height fog over the terrain's extent only.
geometry::FroxelOptions scene_froxel_options(const geometry::Scene& scene, const geometry::Terrain& terrain);
//! The CPU reference's view of `camera` at width x height, ending at view depth max_depth (the
//! froxel volume's far plane; 0: no limit).
geometry::ReferenceView reference_view(const Camera& camera, int width, int height, double max_depth);
//! The lighting the CPU reference judges a scene's fog with (the renderers' model).
geometry::FogLighting scene_fog_lighting(const geometry::Scene& scene, const geometry::Medium* medium,
                                         const geometry::FroxelOptions& froxel);

//! What a mode needs besides the scene's fog: the particles it sampled (combined: only the
//! particles' share of the Medium) and the froxel options. The renderer keeps references into
//! it and into `fog`, so both must outlive its use by the renderer.
class SceneRendering {
public:
    //! fog: the scene's fog (author_scene_fog), null when the scene has none.
    //! \throw InputError naming the scene when the mode needs fog the scene does not have.
    SceneRendering(const geometry::Scene& scene, const geometry::Terrain& terrain, const geometry::SceneFog* fog,
                   FogMode mode);

    //! Sets the renderer up for the mode: what it draws, and clears the rest.
    void apply(Renderer& renderer) const;
    //! Frames to draw before a still picture is final: the froxels' temporal filter's jittered
    //! cycle (15 of its 16 frames) when the mode draws froxels with it, else 0.
    int warmup_frames() const;

    FogMode mode() const { return mode_; }
    bool draws_layers() const { return fog_ && (mode_ == FogMode::layers || mode_ == FogMode::combined); }
    bool draws_froxels() const;
    const std::optional<geometry::ParticleCloud>& particles() const { return particles_; }
    const geometry::FroxelOptions& froxel_options() const { return froxel_; }

private:
    FogMode mode_;
    const geometry::Scene& scene_;
    const geometry::SceneFog* fog_;
    geometry::FroxelOptions froxel_;
    std::optional<geometry::ParticleCloud> particles_;
};

}  // namespace kiri::render
