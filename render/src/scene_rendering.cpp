#include "kiri/render/scene_rendering.hpp"

#include <cmath>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/medium/air_light.hpp"
#include "kiri/geometry/medium/fog_partition.hpp"

namespace kiri::render {
namespace {

// The time the scene's fog is drawn at (wind drift and dissipation).
double scene_time(const geometry::Scene& scene) { return scene.medium.time; }

bool has_haze(const geometry::Scene& scene) { return geometry::world_froxel_options(scene).height_fog.enabled(); }

void check_mode(const geometry::Scene& scene, FogMode mode)
{
    const std::string label = scene.file.string();
    if ((mode == FogMode::layers || mode == FogMode::particles) && !scene.fog)
        throw InputError(label, "/fog", std::string("mode ") + to_string(mode) + " needs a fog section");
    if ((mode == FogMode::froxel || mode == FogMode::combined) && !scene.fog && !has_haze(scene))
        throw InputError(label, "/fog",
                         std::string("mode ") + to_string(mode) + " needs a fog section or a froxel height fog");
}

}  // namespace

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

geometry::PipelineTarget pipeline_target(FogMode mode, const geometry::Scene& scene)
{
    geometry::PipelineTarget target;
    target.up_to = geometry::Stage::layer_base;
    target.particles = geometry::ParticleSet::none;
    switch (mode) {
    case FogMode::terrain: target.up_to = geometry::Stage::terrain; break;
    case FogMode::layers: target.up_to = geometry::Stage::medium; break;  // the sun volume's
    case FogMode::froxel: target.up_to = geometry::Stage::medium; break;
    case FogMode::particles:
        target.up_to = geometry::Stage::particles;
        target.particles = geometry::ParticleSet::whole;
        break;
    case FogMode::combined:
        // The particles stand for their share of the Medium only: its top band.
        target.up_to = geometry::Stage::particles;
        target.particles =
            scene.combined.particle_share > 0.0 ? geometry::ParticleSet::top_band : geometry::ParticleSet::none;
        break;
    }
    // The Medium's model `baked` reads its light volume (the light stage runs for it alone).
    if (mode != FogMode::terrain && scene.medium.multiple_scattering == geometry::MultipleScattering::baked)
        target.up_to = geometry::Stage::light;
    return target;
}

FogMode default_mode(const geometry::Scene& scene)
{
    return scene.fog || has_haze(scene) ? FogMode::combined : FogMode::terrain;
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
    s.near_scale = o.near_scale;
    s.near_pixels = o.near_pixels;
    s.near_field = o.near_field;
    s.match_medium = o.match_medium;
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

geometry::AirLight terrain_air(const geometry::Terrain* terrain, const glm::dvec3& ambient, bool sky)
{
    if (!terrain)
        return {};
    const geometry::Bounds3 b = terrain->bounds();
    return geometry::scene_air(std::hypot(b.max.x - b.min.x, b.max.y - b.min.y), ambient, sky);
}

geometry::FogLighting scene_fog_lighting(const geometry::Scene& scene, const geometry::Terrain* terrain,
                                         const geometry::Medium* medium, const geometry::FroxelOptions& froxel,
                                         std::shared_ptr<const geometry::LightVolume> light_volume)
{
    geometry::FogLighting light;
    light.sun_direction = scene.sun.direction;
    light.sun_radiance = scene.sun.color * scene.sun.intensity;
    light.ambient = scene.sun.ambient;
    light.terrain_shadows = froxel.terrain_shadows;
    light.fog_shadows = froxel.fog_shadows;
    light.multiple_scattering = geometry::multiple_scattering_of(medium);
    light.scattering_octaves = geometry::scattering_octaves_of(medium);
    light.light_volume = std::move(light_volume);
    light.air = terrain_air(terrain, scene.sun.ambient);
    return light;
}

SceneRendering::SceneRendering(const geometry::Scene& scene, const geometry::PipelineProducts& products, FogMode mode)
{
    update(scene, products, mode);
}

void SceneRendering::update(const geometry::Scene& scene, const geometry::PipelineProducts& products, FogMode mode)
{
    check_mode(scene, mode);
    // Everything that can throw first: a failed update keeps the last good rendering.
    const geometry::FroxelOptions froxel =
        products.terrain ? scene_froxel_options(scene, *products.terrain) : geometry::world_froxel_options(scene);
    const geometry::LayerOptions layers =
        products.has_fog() ? geometry::fog_layer_options(scene, products.fog) : geometry::LayerOptions{};
    if (products.medium != products_.medium)
        timed_medium_.reset();
    const double time = scene_time(scene);
    if (products.medium && products.medium->detail().time != time) {
        if (!timed_medium_)  // one copy per Medium, moved in time from then on
            timed_medium_ = std::make_shared<geometry::Medium>(*products.medium);
        timed_medium_->set_time(time);
    } else {
        timed_medium_.reset();
    }
    mode_ = mode;
    scene_ = scene;
    products_ = products;
    froxel_ = froxel;
    layers_ = layers;
}

bool SceneRendering::draws_layers() const
{
    return products_.has_fog() && (mode_ == FogMode::layers || mode_ == FogMode::combined);
}

bool SceneRendering::draws_froxels() const
{
    // The Medium while the fog has one, else the height fog alone.
    return (mode_ == FogMode::froxel || mode_ == FogMode::combined) && (medium() || froxel_.height_fog.enabled());
}

const geometry::ParticleCloud* SceneRendering::particles() const
{
    return mode_ == FogMode::particles || mode_ == FogMode::combined ? products_.particles.get() : nullptr;
}

const geometry::Medium* SceneRendering::medium() const
{
    if ((mode_ != FogMode::froxel && mode_ != FogMode::combined) || !products_.has_fog())
        return nullptr;
    return timed_medium_ ? timed_medium_.get() : products_.medium.get();
}

const geometry::Medium* SceneRendering::sun_medium() const
{
    if (mode_ == FogMode::terrain || !products_.has_fog())
        return nullptr;
    return timed_medium_ ? timed_medium_.get() : products_.medium.get();
}

SunLight SceneRendering::sun() const
{
    SunLight sun = to_sun(scene_.sun);
    sun.terrain_shadows = froxel_.terrain_shadows;
    sun.shadow_map_size = froxel_.shadow_map_size;
    sun.esm_sharpness = froxel_.esm_sharpness;
    return sun;
}

void SceneRendering::apply(Renderer& renderer) const
{
    renderer.set_sun(sun());
    renderer.set_layer_resolution(scene_.layers.resolution);
    if (draws_layers())
        renderer.set_layers(*products_.layer_base, layers_);
    else
        renderer.clear_layers();
    if (const geometry::ParticleCloud* cloud = particles())
        renderer.set_particles(*cloud, particle_style(scene_.particles));
    else
        renderer.clear_particles();
    if (draws_froxels())
        renderer.set_froxel_fog(medium(), froxel_);
    else
        renderer.clear_froxel_fog();
    // The fog drawn shades the sun for every renderer and the ground under it; a height fog only
    // the froxels draw shades nothing where they do not.
    renderer.set_sun_medium(sun_medium(), draws_froxels() ? froxel_.height_fog : geometry::HeightFog{});
    // The baked multiple scattering, where the Medium's model is `baked` (the pipeline's light
    // stage made it for the scene's sun); the renderers draw single scattering without it.
    if (mode_ != FogMode::terrain && products_.light_volume)
        renderer.set_light_volume(products_.light_volume, products_.medium.get());
    else
        renderer.set_light_volume(nullptr, nullptr);
    std::optional<geometry::FogPartition> partition;
    if (mode_ == FogMode::combined) {
        partition = scene_.combined;
        const geometry::ParticleCloud* cloud = particles();
        if (cloud && !cloud->particles.empty())
            partition->particle_radius = cloud->share_radius;  // the depth counted as the sampler did
        else
            partition->particle_share = 0.0;  // no particles drawn: nobody else may leave their share out
    }
    renderer.set_fog_partition(partition);
}

}  // namespace kiri::render
