#pragma once
//! \file scene_rendering.hpp
//! One place that turns a scene, the pipeline's products and a render mode into what the
//! Renderer draws, so `kiri render`, `kiri bench` and the preview agree: terrain, layers,
//! particles, froxel, or combined (docs/combined.md: every renderer draws its share of the one
//! Medium: froxels at every distance, or near and the layers far, particles in the top band,
//! set_fog_partition).
#include <memory>
#include <optional>
#include <string_view>

#include "kiri/geometry/medium/fog_lighting.hpp"
#include "kiri/geometry/reference/reference_fog.hpp"
#include "kiri/geometry/scene/pipeline.hpp"
#include "kiri/geometry/scene/scene.hpp"
#include "kiri/geometry/volume/froxel_options.hpp"
#include "kiri/render/renderer.hpp"

namespace kiri::render {

enum class FogMode { terrain, layers, particles, froxel, combined };

const char* to_string(FogMode mode);
//! False for any other name.
bool parse_fog_mode(std::string_view name, FogMode& out);

//! What a mode asks of the pipeline: how far a run goes and which particles it samples.
geometry::PipelineTarget pipeline_target(FogMode mode, const geometry::Scene& scene);
//! The mode `kiri render` draws by default: combined when the scene has fog (a fog section or a
//! froxel height fog), else terrain.
FogMode default_mode(const geometry::Scene& scene);

Camera to_camera(const geometry::CameraSpec& camera);
SunLight to_sun(const geometry::SunSpec& sun);
ParticleStyle particle_style(const geometry::ParticleOptions& options);
//! The scene's froxel options in world units, its height fog over the terrain's extent only.
geometry::FroxelOptions scene_froxel_options(const geometry::Scene& scene, const geometry::Terrain& terrain);
//! The CPU reference's view of `camera` at width x height, ending at view depth max_depth (the
//! froxel volume's far plane; 0: no limit).
geometry::ReferenceView reference_view(const Camera& camera, int width, int height, double max_depth);
//! The air the renderer draws over `terrain` (its extent's diagonal, geometry::scene_air) under a
//! sky light `ambient`; `sky` false or no terrain: none.
geometry::AirLight terrain_air(const geometry::Terrain* terrain, const glm::dvec3& ambient, bool sky = true);
//! The lighting the CPU reference judges a scene's fog with (the renderers' model), with the
//! pipeline's light volume for the model `baked` (PipelineProducts::light_volume; null: none)
//! and the air over `terrain` (geometry::scene_air, as the renderer draws it; null: no air).
geometry::FogLighting scene_fog_lighting(const geometry::Scene& scene, const geometry::Terrain* terrain,
                                         const geometry::Medium* medium, const geometry::FroxelOptions& froxel,
                                         std::shared_ptr<const geometry::LightVolume> light_volume = nullptr);

//! A scene drawn in one mode from the pipeline's products (pipeline_target(mode, scene)). It
//! keeps the products it was given, so what the renderer refers to lives as long as it does.
class SceneRendering {
public:
    //! \throw InputError naming the scene when the mode needs fog the scene does not have.
    SceneRendering(const geometry::Scene& scene, const geometry::PipelineProducts& products, FogMode mode);

    //! The same rendering for an edited scene or newer products (the preview): what did not
    //! change is kept, e.g. the Medium at the scene's time (wind and dissipation play without a
    //! new Medium). \throw InputError as the constructor.
    void update(const geometry::Scene& scene, const geometry::PipelineProducts& products, FogMode mode);

    //! Sets the renderer up for the mode: what it draws, and clears the rest. Parts the products
    //! do not have yet (a medium still being made) are left out.
    void apply(Renderer& renderer) const;

    FogMode mode() const { return mode_; }
    bool draws_layers() const;
    bool draws_froxels() const;
    bool draws_particles() const { return particles() != nullptr; }
    //! The particles drawn (null: none).
    const geometry::ParticleCloud* particles() const;
    //! The Medium the froxels draw, at the scene's time (null: none).
    const geometry::Medium* medium() const;
    //! The Medium the sun shines through for the renderers' tau_sun and the ground's shade
    //! (TerrainPass::set_fog_shade), at the scene's time: the fog's in every mode that draws fog
    //! (null: terrain mode, no fog, or not made yet).
    const geometry::Medium* sun_medium() const;
    const geometry::FroxelOptions& froxel_options() const { return froxel_; }
    //! The scene's sun with the terrain's shadows as the scene sets them (its froxel keys
    //! terrain_shadows, shadow_map_size, esm_sharpness: one shadow map for every renderer).
    SunLight sun() const;
    const geometry::PipelineProducts& products() const { return products_; }

private:
    FogMode mode_ = FogMode::terrain;
    geometry::Scene scene_;
    geometry::PipelineProducts products_;
    geometry::FroxelOptions froxel_;
    geometry::LayerOptions layers_;
    //! The products' Medium moved to the scene's time when the two differ (else null).
    std::shared_ptr<geometry::Medium> timed_medium_;
};

}  // namespace kiri::render
