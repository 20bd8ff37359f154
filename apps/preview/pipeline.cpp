#include "pipeline.hpp"

#include <exception>
#include <utility>

#include "kiri/geometry/scene/author_estimate.hpp"
#include "kiri/geometry/layers/layer_medium.hpp"
#include "kiri/geometry/placement/fill_medium.hpp"
#include "kiri/geometry/medium/fog_partition.hpp"
#include "kiri/geometry/scene/fog_spec.hpp"

namespace kiri::preview {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_between(Clock::time_point a, Clock::time_point b)
{
    return std::chrono::duration<double>(b - a).count();
}

// Stage keys: the JSON of a copy of the scene that keeps only what the stage reads and resets
// the rest to defaults. A key written this way stays conservative when the scene grows: a new
// key that is not reset here makes the stage rerun, never skip.
std::string terrain_key(const geometry::Scene& s)
{
    geometry::Scene k;
    k.terrain = s.terrain;
    return geometry::scene_to_json(k);
}

std::string fog_key(const geometry::Scene& s, bool fit, bool tessellation)
{
    geometry::Scene k;
    k.terrain = s.terrain;  // the exaggeration scales the fog's vertical quantities
    k.fog = s.fog;
    if (k.fog && !fit)
        k.fog->fit = {};
    if (k.fog && !tessellation)
        k.fog->tessellation = {};
    return geometry::scene_to_json(k);
}

// The placement reads the fill, outline, flow and burn-off keys and the patch size (the
// outline's defaults); the flow and the burn-off also read the medium's optics (evaporation
// depth, the sun through the fog) unless the scene gives their own.
std::string placement_key(const geometry::Scene& s)
{
    geometry::Scene k;
    k.terrain = s.terrain;
    k.fog = geometry::FogSpec{};
    k.fog->placement = s.fog->placement;
    k.fog->patch_size = s.fog->patch_size;
    if (s.fog->placement->flow || s.fog->placement->burn_off) {
        k.medium.extinction = s.medium.extinction;
        k.medium.anisotropy = s.medium.anisotropy;
    }
    return geometry::scene_to_json(k);
}

// The medium: the layer base it is made from (its version), the medium's options and the
// layers' (their count shifts the noise). The medium's time is left out: playing it would
// resample every frame.
std::string medium_key(const geometry::Scene& s, std::uint64_t base_version)
{
    geometry::Scene k;
    k.medium = s.medium;
    k.medium.time = 0.0;
    k.layers = s.layers;
    k.layers.resolution = geometry::LayerOptions{}.resolution;  // the layer pass's, per frame
    return std::to_string(base_version) + geometry::scene_to_json(k);
}

// The particles: the medium (its version), the sampling options and, in combined rendering,
// the partition; the attenuation buffer's and the billboards' options apply per frame.
std::string particles_key(const geometry::Scene& s, std::uint64_t medium_version, bool share)
{
    geometry::Scene k;
    k.particles = s.particles;
    if (share)
        k.combined = s.combined;
    const geometry::ParticleOptions defaults;
    k.particles.resolution = defaults.resolution;
    k.particles.half_float = defaults.half_float;
    k.particles.frame = defaults.frame;
    k.particles.soft_edge = defaults.soft_edge;
    return std::to_string(medium_version) + (share ? "share" : "") + geometry::scene_to_json(k);
}

std::string layer_base_key(const geometry::Scene& s)
{
    geometry::Scene k;
    k.terrain = s.terrain;
    k.fog = s.fog;
    k.layers.texture = s.layers.texture;
    return geometry::scene_to_json(k);
}

}  // namespace

const char* stage_name(Stage stage)
{
    static const char* names[stage_count] = {"terrain",    "placement", "control mesh", "fit",      "tessellation",
                                             "layer base", "views",     "medium",       "particles"};
    return names[int(stage)];
}

struct Pipeline::Cache {
    std::string terrain_key, placement_key, control_key, fit_key, tessellation_key, layer_key, medium_key,
        particles_key;
    std::shared_ptr<const geometry::Terrain> terrain;
    std::shared_ptr<const geometry::PlacedFog> placed;
    std::optional<geometry::BaseSurface> surface;  // refitted in place (its samples are reused)
    geometry::FitReport fit;
    std::optional<geometry::Tessellation> tessellation;
    std::shared_ptr<const geometry::LayerBase> base;
    double base_offset = 0.0;
    std::shared_ptr<const FogViews> views;
    std::shared_ptr<const FogProducts> fog;  // the last good fog
    // Versions of the layer base (and placement) and of the medium: the keys of what follows.
    std::uint64_t base_version = 0, medium_version = 0;
    std::shared_ptr<const geometry::Medium> medium;
    std::shared_ptr<const geometry::ParticleCloud> particles;

    void forget_fog_from(Stage stage)
    {
        if (stage <= Stage::placement)
            placement_key.clear();
        if (stage <= Stage::control_mesh)
            control_key.clear();
        if (stage <= Stage::fit)
            fit_key.clear();
        if (stage <= Stage::tessellation)
            tessellation_key.clear();
        layer_key.clear();
    }
};

Pipeline::Pipeline() : cache_(std::make_unique<Cache>()), worker_([this] { run(); }) {}

Pipeline::~Pipeline()
{
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    worker_.join();
}

std::uint64_t Pipeline::request(const geometry::Scene& scene, Needs needs)
{
    std::uint64_t generation = 0;
    {
        std::lock_guard lock(mutex_);
        pending_ = scene;
        pending_needs_ = needs;
        generation = ++status_.requested;
    }
    wake_.notify_all();
    return generation;
}

std::optional<Products> Pipeline::take()
{
    std::lock_guard lock(mutex_);
    return std::exchange(result_, std::nullopt);
}

void Pipeline::wait_idle()
{
    std::unique_lock lock(mutex_);
    idle_.wait(lock, [this] { return status_.finished == status_.requested; });
}

PipelineStatus Pipeline::status() const
{
    std::lock_guard lock(mutex_);
    PipelineStatus s = status_;
    const Clock::time_point now = Clock::now();
    if (s.busy) {
        s.stage_seconds = seconds_between(stage_start_, now);
        s.job_seconds = seconds_between(job_start_, now);
    }
    return s;
}

void Pipeline::run()
{
    for (;;) {
        geometry::Scene scene;
        Needs needs;
        std::uint64_t generation = 0;
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [this] { return stop_ || pending_.has_value(); });
            if (stop_)
                return;
            scene = std::move(*pending_);
            needs = pending_needs_;
            pending_.reset();
            generation = status_.requested;
            status_.busy = true;
            job_start_ = stage_start_ = Clock::now();
        }
        Products products = compute(scene, needs, generation);
        {
            std::lock_guard lock(mutex_);
            result_ = std::move(products);
            status_.finished = generation;
            status_.busy = pending_.has_value();
        }
        idle_.notify_all();
    }
}

void Pipeline::publish_partial(const Products& partial)
{
    std::lock_guard lock(mutex_);
    result_ = partial;
}

void Pipeline::enter(Stage stage)
{
    std::lock_guard lock(mutex_);
    status_.stage = stage;
    stage_start_ = Clock::now();
}

void Pipeline::leave(Stage stage)
{
    std::lock_guard lock(mutex_);
    StageRecord& r = status_.stages[int(stage)];
    ++r.runs;
    r.last_seconds = seconds_between(stage_start_, Clock::now());
}

Products Pipeline::compute(const geometry::Scene& scene, Needs needs, std::uint64_t generation)
{
    Cache& c = *cache_;
    Products out;
    out.generation = generation;
    out.scene = scene;
    const std::string label = scene.file.string();
    Stage stage = Stage::terrain;
    // Runs a stage when its key changed; a failure leaves the key empty, so it reruns next time.
    auto step = [&](Stage s, std::string& cached_key, const std::string& key, auto&& work) {
        stage = s;
        if (cached_key == key)
            return;
        cached_key.clear();
        enter(s);
        work();
        leave(s);
        cached_key = key;
        out.rebuilt[int(s)] = true;
    };
    try {
        step(Stage::terrain, c.terrain_key, terrain_key(scene), [&] {
            c.terrain = std::make_shared<const geometry::Terrain>(geometry::load_scene_terrain(scene));
            c.forget_fog_from(Stage::placement);
        });
        out.terrain = c.terrain;
        if (out.rebuilt[int(Stage::terrain)] && scene.fog) {
            Products partial = out;
            partial.fog = c.fog;  // the old fog over the new terrain until the fit is done
            publish_partial(partial);
        }
        if (!scene.fog) {
            c.forget_fog_from(Stage::placement);
            c.placed.reset();
            c.fog.reset();
            return out;
        }
        geometry::FogSpec spec = geometry::world_fog_spec(scene);
        geometry::LayerOptions layers = geometry::world_layer_options(scene);
        const geometry::Terrain& terrain = *c.terrain;
        if (spec.placement) {
            // As author_scene_fog: the placed footprint and lake target, and a layer stack as
            // deep as the deepest fog, hanging from its top.
            step(Stage::placement, c.placement_key, placement_key(scene), [&] {
                geometry::check_author_estimate(geometry::estimate_author(spec, terrain.heightfield(), layers.count),
                                                label);
                c.placed.reset();
                c.placed = std::make_shared<const geometry::PlacedFog>(
                    geometry::place_fog(terrain, *spec.placement, spec.patch_size, label));
                c.forget_fog_from(Stage::control_mesh);
            });
            spec = geometry::placed_fog_spec(spec, *c.placed);
            layers.thickness = spec.fit.thickness;
            geometry::validate_layer_options(layers, label);
        } else {
            c.placement_key.clear();
            c.placed.reset();
        }
        layers.base_offset = spec.fit.mode == geometry::FitMode::lake ? -layers.thickness : 0.0;
        step(Stage::control_mesh, c.control_key, fog_key(scene, false, false), [&] {
            geometry::check_author_estimate(geometry::estimate_author(spec, terrain.heightfield(), layers.count),
                                            label);
            c.surface.reset();  // free the old one first: it can be large
            c.surface = geometry::fog_control_surface(terrain, spec, label);
            c.forget_fog_from(Stage::fit);
        });
        step(Stage::fit, c.fit_key, fog_key(scene, true, false), [&] {
            c.fit = geometry::fit_fog_surface(*c.surface, terrain, spec, label);
            c.forget_fog_from(Stage::tessellation);
        });
        bool new_surface = false;
        step(Stage::tessellation, c.tessellation_key, fog_key(scene, true, true), [&] {
            c.tessellation = geometry::tessellate(*c.surface, spec.tessellation);
            new_surface = true;
        });
        step(Stage::layer_base, c.layer_key, layer_base_key(scene), [&] {
            c.base = std::make_shared<const geometry::LayerBase>(
                geometry::make_layer_base(*c.surface, *c.tessellation, layers, label));
            c.base_offset = layers.base_offset;
            ++c.base_version;
        });
        if (new_surface || !c.views) {
            stage = Stage::views;
            enter(Stage::views);
            c.views = make_fog_views(*c.surface, *c.tessellation, terrain, spec.fit);
            leave(Stage::views);
            out.rebuilt[int(Stage::views)] = true;
        }
        if (!c.fog || c.fog->base != c.base || c.fog->views != c.views) {
            auto fog = std::make_shared<FogProducts>();
            fog->base = c.base;
            fog->base_offset = c.base_offset;
            fog->views = c.views;
            fog->placed = c.placed;
            fog->placed_thickness = c.placed ? layers.thickness : 0.0;
            fog->fit = c.fit;
            fog->patches = c.surface->num_patches();
            fog->triangles = c.tessellation->mesh.n_faces();
            fog->tessellation_error = c.tessellation->max_error;
            fog->min = c.base->min - glm::dvec3(0.0, 0.0, c.base_offset);
            fog->max = c.base->max - glm::dvec3(0.0, 0.0, c.base_offset);
            c.fog = std::move(fog);
        }
        out.fog = c.fog;
        if (needs.medium || needs.particles) {
            step(Stage::medium, c.medium_key, medium_key(scene, c.base_version), [&] {
                c.medium.reset();
                c.medium = std::make_shared<const geometry::Medium>(
                    c.placed ? geometry::fill_medium(terrain, *c.placed, scene.medium,
                                                     geometry::medium_detail(scene.medium, layers.count), label)
                             : geometry::make_medium(*c.base, layers, terrain, scene.medium, label));
                ++c.medium_version;
            });
            out.medium = c.medium;
        }
        if (needs.particles) {
            const bool share = needs.particle_share;
            step(Stage::particles, c.particles_key, particles_key(scene, c.medium_version, share), [&] {
                c.particles.reset();
                const geometry::Medium& medium = *c.medium;
                const geometry::FogPartition partition = scene.combined;
                if (!share)
                    c.particles = std::make_shared<const geometry::ParticleCloud>(
                        geometry::sample_particles(medium, scene.particles, label));
                else if (partition.particle_share > 0.0)  // as SceneRendering samples them
                    c.particles = std::make_shared<const geometry::ParticleCloud>(
                        geometry::sample_particles(medium, scene.particles, label, [&](const glm::dvec3& p) {
                            return geometry::particle_share(partition, medium.height_fraction(p));
                        }));
            });
            out.particles = c.particles;
        }
    } catch (const std::exception& e) {
        out.error = std::string(stage_name(stage)) + ": " + e.what();
        out.terrain = c.terrain;
        out.fog = c.fog;  // the last good fog stays on screen
        out.medium = needs.medium || needs.particles ? c.medium : nullptr;
        out.particles = needs.particles ? c.particles : nullptr;
    }
    return out;
}

}  // namespace kiri::preview
