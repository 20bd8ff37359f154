#include "kiri/geometry/scene/pipeline.hpp"

#include <chrono>
#include <exception>
#include <new>

#include "kiri/geometry/core/error.hpp"

#include "kiri/geometry/layers/layer_medium.hpp"
#include "kiri/geometry/placement/fill_medium.hpp"
#include "kiri/geometry/reference/light_volume_bake.hpp"
#include "kiri/geometry/scene/author_estimate.hpp"
#include "scene/stage_inputs.hpp"

namespace kiri::geometry {
namespace {

using Clock = std::chrono::steady_clock;

// The stage functions: each a pure function of its inputs (and of what the stages it reads made).

std::shared_ptr<const Medium> build_medium(const Terrain& terrain, const PlacedFog* placed, const LayerBase& base,
                                           const MediumOptions& medium, const LayerOptions& layers,
                                           const std::string& label)
{
    // Fog placed by the terrain: the fill's columns are the shell; else the layer stack's slab.
    return std::make_shared<const Medium>(placed ? fill_medium(terrain, *placed, medium, medium_detail(medium), label)
                                                 : make_medium(base, layers, terrain, medium, label));
}

// The light stage runs for the Medium's model `baked` alone.
bool baked(const Scene& scene) { return scene.medium.multiple_scattering == MultipleScattering::baked; }

// What the bake reads: the Medium, the terrain (hiding and absorbing), the sun, and the froxels'
// height fog over the terrain's extent (render::scene_froxel_options takes the same).
LightInput light_input(const Scene& scene, std::uint64_t medium, std::uint64_t terrain_version, const Terrain& terrain)
{
    LightInput in;
    in.medium = medium;
    in.terrain = terrain_version;
    in.sun = scene.sun.direction;
    in.haze = world_froxel_options(scene).height_fog;
    const Bounds3 b = terrain.bounds();
    in.haze.min = {b.min.x, b.min.y};
    in.haze.max = {b.max.x, b.max.y};
    in.surround = scene.terrain.surround;
    return in;
}

std::shared_ptr<const ParticleCloud> build_particles(const Medium& medium, const Terrain& terrain,
                                                     const ParticlesInput& in, const std::string& label)
{
    // The particles stand for their share of the Medium only (its top band in combined mode).
    if (in.set == ParticleSet::top_band && !(in.partition.particle_share > 0.0))
        return nullptr;
    ParticleCloud cloud = in.set == ParticleSet::top_band
        ? sample_particles(medium, in.options, label, particle_height_share(in.partition))
        : sample_particles(medium, in.options, label);
    set_above_ground(cloud, medium, [&terrain](double x, double y) { return terrain.height(x, y); });
    return std::make_shared<const ParticleCloud>(std::move(cloud));
}

}  // namespace

const char* to_string(Stage stage)
{
    static const char* names[stage_count] = {"terrain",    "placement", "control mesh", "fit",   "tessellation",
                                             "layer base", "medium",    "particles",    "light", "exports"};
    return names[int(stage)];
}

// Per stage: the inputs of its last good run (empty: never ran, or failed), the version of its
// product (the key of the stages that read it) and the product.
template <class Input, class Product>
struct StageCache {
    std::optional<Input> input;
    std::uint64_t version = 0;
    Product product{};
};

struct Pipeline::Cache {
    StageCache<TerrainInput, std::shared_ptr<const Terrain>> terrain;
    double exaggeration = 1.0;  // the terrain's, given or derived
    // The scene with its derived defaults, for the terrain's version and scene it was made from.
    std::optional<std::pair<std::uint64_t, Scene>> resolved_from;
    std::shared_ptr<const Scene> resolved;
    std::shared_ptr<const DerivedDefaults> derived;
    StageCache<PlacementInput, std::shared_ptr<const PlacedFog>> placement;
    // The control mesh's surface is refitted in place by the fit (its samples are reused).
    StageCache<ControlMeshInput, std::unique_ptr<BaseSurface>> control;
    StageCache<FitInput, std::shared_ptr<const SurfaceSummary>> fit;
    StageCache<TessellationInput, std::shared_ptr<const Tessellation>> tessellation;
    StageCache<LayerBaseInput, std::shared_ptr<const LayerBase>> layer_base;
    StageCache<MediumInput, std::shared_ptr<const Medium>> medium;
    StageCache<ParticlesInput, std::shared_ptr<const ParticleCloud>> particles;
    StageCache<LightInput, std::shared_ptr<const LightVolume>> light;
    StageCache<ExportsInput, std::shared_ptr<const std::vector<LayerMesh>>> exports;
    bool fitted = false;  // the control surface holds the fit of `fit.input`
    // The fog section as the last good layer base was made for (world units, placed).
    FogSpec fog;
    LayerOptions layers;
    bool placed = false;

    // A scene without fog: nothing of the fog is kept (it can be large).
    void forget_fog()
    {
        placement = {};
        control = {};
        fit = {};
        tessellation = {};
        layer_base = {};
        medium = {};
        particles = {};
        light = {};
        exports = {};
        fitted = false;
        fog = {};
        layers = {};
        placed = false;
    }
};

Pipeline::Pipeline() : cache_(std::make_unique<Cache>()) {}
Pipeline::~Pipeline() = default;

const BaseSurface* Pipeline::surface() const { return cache_->fitted ? cache_->control.product.get() : nullptr; }

LayerOptions fog_layer_options(const Scene& scene, const FogSpec& spec)
{
    LayerOptions layers = world_layer_options(scene);
    if (spec.placement) {
        // Fog placed by the terrain: a stack as deep as the deepest fog.
        layers.thickness = spec.fit.thickness;
        validate_layer_options(layers, scene.file.string());
    }
    // A lake's fitted surface is its top: the stack hangs one thickness below it.
    if (spec.fit.mode == FitMode::lake)
        layers.base_offset = -layers.thickness;
    return layers;
}

const PipelineProducts& Pipeline::run(const Scene& given_scene, const PipelineTarget& target)
{
    Cache& c = *cache_;
    const Scene& input = given_scene;
    const std::string label = input.file.string();
    ran_.fill(false);
    failed_.reset();
    Stage current = Stage::terrain;
    const auto reaches = [&](Stage s) { return int(target.up_to) >= int(s); };
    // Runs stage s when its inputs differ from its last good run's; a stage that throws keeps
    // no inputs, so it runs again next time.
    const auto step = [&](Stage s, auto& cache, auto input, auto&& compute) {
        current = s;
        if (cache.input && *cache.input == input)
            return;
        cache.input.reset();
        if (observer_)
            observer_(s, false);
        const Clock::time_point start = Clock::now();
        compute(input);
        StageRecord& r = records_[std::size_t(s)];
        ++r.runs;
        r.seconds = std::chrono::duration<double>(Clock::now() - start).count();
        cache.input = std::move(input);
        ++cache.version;
        ran_[std::size_t(s)] = true;
        if (observer_)
            observer_(s, true);
    };
    try {
        step(Stage::terrain, c.terrain, TerrainInput{input.terrain, input.gives("/terrain/exaggeration")},
             [&](const TerrainInput&) {
                 c.terrain.product.reset();  // free the old one first: it can be large
                 c.terrain.product = std::make_shared<const Terrain>(load_scene_terrain(input, &c.exaggeration));
                 products_.terrain = c.terrain.product;
             });
        // The keys the scene leaves out, derived once per terrain and scene (the preview runs
        // this per edit).
        if (!c.resolved_from || c.resolved_from->first != c.terrain.version || c.resolved_from->second != input) {
            c.resolved_from.reset();
            auto derived = std::make_shared<DerivedDefaults>();
            c.resolved = std::make_shared<const Scene>(
                derive_scene_defaults(input, *c.terrain.product, c.exaggeration, *derived));
            c.derived = std::move(derived);
            c.resolved_from.emplace(c.terrain.version, input);
        }
        const Scene& scene = *c.resolved;
        products_.scene = c.resolved;
        products_.derived = c.derived;
        if (!scene.fog) {
            c.forget_fog();
            products_ = PipelineProducts{c.terrain.product, c.resolved, c.derived};
            return products_;
        }
        const Terrain& terrain = *c.terrain.product;
        FogSpec spec = world_fog_spec(scene);
        std::uint64_t placement_version = 0;
        const PlacedFog* placed = nullptr;
        if (spec.placement) {
            // The estimate comes before any large allocation.
            check_author_estimate(estimate_author(spec, terrain.heightfield(), scene.layers.count), label);
            step(Stage::placement, c.placement, PlacementInput{c.terrain.version, *spec.placement, spec.patch_size},
                 [&](const PlacementInput& in) {
                     c.placement.product.reset();
                     c.placement.product =
                         std::make_shared<const PlacedFog>(place_fog(terrain, in.placement, in.patch_size, label));
                 });
            placed = c.placement.product.get();
            placement_version = c.placement.version;
            spec = placed_fog_spec(spec, *placed);
        }
        const LayerOptions layers = fog_layer_options(scene, spec);
        check_author_estimate(estimate_author(spec, terrain.heightfield(), layers.count), label);

        step(Stage::control_mesh, c.control, control_mesh_input(c.terrain.version, placement_version, spec),
             [&](const ControlMeshInput&) {
                 c.fitted = false;
                 c.control.product.reset();
                 c.control.product = std::make_unique<BaseSurface>(fog_control_surface(terrain, spec, label));
             });
        BaseSurface& surface = *c.control.product;
        step(Stage::fit, c.fit, FitInput{c.control.version, spec.fit}, [&](const FitInput&) {
            c.fitted = false;
            const FitReport report = fit_fog_surface(surface, terrain, spec, label);
            c.fitted = true;
            c.fit.product = std::make_shared<const SurfaceSummary>(summarise(surface, report));
        });
        step(Stage::tessellation, c.tessellation, TessellationInput{c.fit.version, spec.tessellation},
             [&](const TessellationInput& in) {
                 c.tessellation.product.reset();
                 c.tessellation.product = std::make_shared<const Tessellation>(tessellate(surface, in.tessellation));
             });
        step(Stage::layer_base, c.layer_base, layer_base_input(c.tessellation.version, layers),
             [&](const LayerBaseInput&) {
                 c.layer_base.product = std::make_shared<const LayerBase>(
                     make_layer_base(surface, *c.tessellation.product, layers, label));
             });
        c.fog = spec;
        c.layers = layers;
        c.placed = placed != nullptr;
        if (reaches(Stage::medium)) {
            const std::uint64_t source = placed ? placement_version : c.layer_base.version;
            step(Stage::medium, c.medium, medium_input(source, placed != nullptr, scene.medium, layers),
                 [&](const MediumInput&) {
                     c.medium.product.reset();
                     c.medium.product =
                         build_medium(terrain, placed, *c.layer_base.product, scene.medium, layers, label);
                 });
        }
        if (reaches(Stage::particles) && target.particles != ParticleSet::none) {
            step(Stage::particles, c.particles,
                 particles_input(c.medium.version, target.particles, scene.particles, scene.combined),
                 [&](const ParticlesInput& in) {
                     c.particles.product.reset();
                     c.particles.product = build_particles(*c.medium.product, terrain, in, label);
                 });
        }
        if (reaches(Stage::light) && target.light && baked(scene)) {
            step(Stage::light, c.light, light_input(scene, c.medium.version, c.terrain.version, terrain),
                 [&](const LightInput& in) {
                     c.light.product.reset();
                     LightVolumeOptions bake;
                     bake.surround = in.surround;
                     c.light.product = std::make_shared<const LightVolume>(
                         bake_light_volume({c.medium.product.get(), in.haze}, &terrain.heightfield(), in.sun, bake));
                 });
        }
        if (reaches(Stage::exports)) {
            step(Stage::exports, c.exports, ExportsInput{c.layer_base.version, layers, target.export_eye},
                 [&](const ExportsInput& in) {
                     c.exports.product = std::make_shared<const std::vector<LayerMesh>>(
                         build_layers(*c.layer_base.product, in.layers, in.eye));
                 });
        }
    } catch (const Error&) {
        failed_ = current;
        publish(target);  // the last good products stay
        throw;
    } catch (const std::bad_alloc&) {
        failed_ = current;
        publish(target);
        throw LimitError(label, to_string(current), "ran out of memory (a smaller terrain or fewer layers would fit)");
    } catch (const std::exception&) {
        // A library's own message (std::, allocator, assertion text) means nothing to a user:
        // name the stage and the scene instead.
        failed_ = current;
        publish(target);
        throw InputError(label, to_string(current),
                         "failed on this input (an internal error: please report it with the scene and its terrain)");
    }
    publish(target);
    return products_;
}

void Pipeline::publish(const PipelineTarget& target)
{
    const Cache& c = *cache_;
    const auto reaches = [&](Stage s) { return int(target.up_to) >= int(s); };
    products_.terrain = c.terrain.product;
    products_.scene = c.resolved;
    products_.derived = c.derived;
    products_.fog = c.fog;
    products_.layers = c.layers;
    products_.placed = c.placed ? c.placement.product : nullptr;
    products_.surface = c.fit.product;
    products_.tessellation = c.tessellation.product;
    products_.layer_base = c.layer_base.product;
    products_.medium = reaches(Stage::medium) ? c.medium.product : nullptr;
    products_.particles =
        reaches(Stage::particles) && target.particles != ParticleSet::none ? c.particles.product : nullptr;
    products_.light_volume =
        reaches(Stage::light) && target.light && c.medium.product && c.resolved && baked(*c.resolved) ? c.light.product
                                                                                                      : nullptr;
    products_.exports = reaches(Stage::exports) ? c.exports.product : nullptr;
}

PipelineProducts author_scene(const Scene& scene, const PipelineTarget& target)
{
    Pipeline pipeline;
    return pipeline.run(scene, target);
}

}  // namespace kiri::geometry
