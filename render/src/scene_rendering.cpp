#include "kiri/render/scene_rendering.hpp"

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/medium/fog_partition.hpp"

namespace kiri::render {

const char* to_string(FogMode mode)
{
    switch (mode) {
    case FogMode::terrain: return "terrain";
    case FogMode::layers: return "layers";
    case FogMode::particles: return "particles";
    case FogMode::froxel: return "froxel";
    default: return "combined";
    }
}

bool parse_fog_mode(std::string_view name, FogMode& out)
{
    for (FogMode m : {FogMode::terrain, FogMode::layers, FogMode::particles, FogMode::froxel, FogMode::combined})
        if (name == to_string(m)) {
            out = m;
            return true;
        }
    return false;
}

Camera to_camera(const geometry::CameraSpec& c)
{
    Camera out;
    out.position = c.position;
    out.target = c.target;
    out.fov_y_deg = c.fov_y_deg;
    return out;
}

SunLight to_sun(const geometry::SunSpec& s) { return {s.direction, s.color, s.intensity, s.ambient}; }

ParticleStyle particle_style(const geometry::ParticleOptions& o)
{
    ParticleStyle s;
    s.buffer.resolution = o.resolution;
    s.buffer.half_float = o.half_float;
    s.buffer.frame = o.frame;
    s.soft_edge = o.soft_edge;
    return s;
}

geometry::FroxelOptions scene_froxel_options(const geometry::Scene& scene, const geometry::Terrain& terrain)
{
    geometry::FroxelOptions options = geometry::world_froxel_options(scene);
    const geometry::Bounds3 b = terrain.bounds();
    options.height_fog.min = {b.min.x, b.min.y};
    options.height_fog.max = {b.max.x, b.max.y};
    return options;
}

geometry::ReferenceView reference_view(const Camera& camera, int width, int height, double max_depth)
{
    geometry::ReferenceView view;
    view.eye = camera.position;
    view.target = camera.target;
    view.fov_y_deg = camera.fov_y_deg;
    view.width = width;
    view.height = height;
    view.max_depth = max_depth;
    return view;
}

geometry::FogLighting scene_fog_lighting(const geometry::Scene& scene, const geometry::Medium* medium,
                                         const geometry::FroxelOptions& froxel)
{
    geometry::FogLighting light;
    light.sun_direction = scene.sun.direction;
    light.sun_radiance = scene.sun.color * scene.sun.intensity;
    light.ambient = scene.sun.ambient;
    light.terrain_shadows = froxel.terrain_shadows;
    light.fog_shadows = froxel.fog_shadows;
    light.scattering_octaves = geometry::scattering_octaves_of(medium);
    return light;
}

SceneRendering::SceneRendering(const geometry::Scene& scene, const geometry::Terrain& terrain,
                               const geometry::SceneFog* fog, FogMode mode)
    : mode_(mode), scene_(scene), fog_(fog), froxel_(scene_froxel_options(scene, terrain))
{
    const std::string label = scene.file.string();
    const bool haze = froxel_.height_fog.enabled();
    if ((mode == FogMode::layers || mode == FogMode::particles) && !fog)
        throw InputError(label, "/fog", std::string("mode ") + to_string(mode) + " needs a fog section");
    if ((mode == FogMode::froxel || mode == FogMode::combined) && !fog && !haze)
        throw InputError(label, "/fog",
                         std::string("mode ") + to_string(mode) + " needs a fog section or a froxel height fog");
    if (mode == FogMode::particles)
        particles_ = geometry::sample_particles(fog->medium, scene.particles, label);
    if (mode == FogMode::combined && fog && scene.combined.particle_share > 0.0) {
        // The particles stand for their share of the Medium only: its top band.
        const geometry::Medium& medium = fog->medium;
        const geometry::FogPartition partition = scene.combined;
        particles_ = geometry::sample_particles(medium, scene.particles, label, [&](const glm::dvec3& p) {
            return geometry::particle_share(partition, medium.height_fraction(p));
        });
    }
}

bool SceneRendering::draws_froxels() const { return mode_ == FogMode::froxel || (mode_ == FogMode::combined); }

void SceneRendering::apply(Renderer& renderer) const
{
    renderer.set_layer_resolution(scene_.layers.resolution);
    if (draws_layers())
        renderer.set_layers(fog_->base, fog_->layers);
    else
        renderer.clear_layers();
    if (particles_)
        renderer.set_particles(*particles_, particle_style(scene_.particles));
    else
        renderer.clear_particles();
    if (draws_froxels())
        renderer.set_froxel_fog(fog_ ? &fog_->medium : nullptr, froxel_);
    else
        renderer.clear_froxel_fog();
    std::optional<geometry::FogPartition> partition;
    if (mode_ == FogMode::combined) {
        partition = scene_.combined;
        if (!particles_)
            partition->particle_share = 0.0;  // no particles drawn: nobody else may leave their share out
    }
    renderer.set_fog_partition(partition);
}

int SceneRendering::warmup_frames() const { return draws_froxels() && froxel_.temporal ? 15 : 0; }

}  // namespace kiri::render
