#include "pipeline.hpp"

#include <exception>
#include <utility>

#include "kiri/geometry/author_estimate.hpp"
#include "kiri/geometry/fog_spec.hpp"

namespace kiri::preview {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_between(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

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
    static const char* names[stage_count] = {"terrain", "control mesh", "fit", "tessellation", "layer base", "views"};
    return names[int(stage)];
}

struct Pipeline::Cache {
    std::string terrain_key, control_key, fit_key, tessellation_key, layer_key;
    std::shared_ptr<const geometry::Terrain> terrain;
    std::optional<geometry::BaseSurface> surface;  // refitted in place (its samples are reused)
    geometry::FitReport fit;
    std::optional<geometry::Tessellation> tessellation;
    std::shared_ptr<const geometry::LayerBase> base;
    double base_offset = 0.0;
    std::shared_ptr<const FogViews> views;
    std::shared_ptr<const FogProducts> fog;  // the last good fog

    void forget_fog_from(Stage stage)
    {
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

std::uint64_t Pipeline::request(const geometry::Scene& scene)
{
    std::uint64_t generation = 0;
    {
        std::lock_guard lock(mutex_);
        pending_ = scene;
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
        std::uint64_t generation = 0;
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [this] { return stop_ || pending_.has_value(); });
            if (stop_)
                return;
            scene = std::move(*pending_);
            pending_.reset();
            generation = status_.requested;
            status_.busy = true;
            job_start_ = stage_start_ = Clock::now();
        }
        Products products = compute(scene, generation);
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

Products Pipeline::compute(const geometry::Scene& scene, std::uint64_t generation)
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
            c.forget_fog_from(Stage::control_mesh);
        });
        out.terrain = c.terrain;
        if (out.rebuilt[int(Stage::terrain)] && scene.fog) {
            Products partial = out;
            partial.fog = c.fog;  // the old fog over the new terrain until the fit is done
            publish_partial(partial);
        }
        if (!scene.fog) {
            c.forget_fog_from(Stage::control_mesh);
            c.fog.reset();
            return out;
        }
        const geometry::FogSpec spec = geometry::world_fog_spec(scene);
        geometry::LayerOptions layers = geometry::world_layer_options(scene);
        const geometry::Terrain& terrain = *c.terrain;
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
            layers.base_offset = spec.fit.mode == geometry::FitMode::lake ? -layers.thickness : 0.0;
            c.base = std::make_shared<const geometry::LayerBase>(
                geometry::make_layer_base(*c.surface, *c.tessellation, layers, label));
            c.base_offset = layers.base_offset;
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
            fog->fit = c.fit;
            fog->patches = c.surface->num_patches();
            fog->triangles = c.tessellation->mesh.n_faces();
            fog->tessellation_error = c.tessellation->max_error;
            fog->min = c.base->min - glm::dvec3(0.0, 0.0, c.base_offset);
            fog->max = c.base->max - glm::dvec3(0.0, 0.0, c.base_offset);
            c.fog = std::move(fog);
        }
        out.fog = c.fog;
    } catch (const std::exception& e) {
        out.error = std::string(stage_name(stage)) + ": " + e.what();
        out.terrain = c.terrain;
        out.fog = c.fog;  // the last good fog stays on screen
    }
    return out;
}

}  // namespace kiri::preview
