#pragma once
//! \file pipeline.hpp
//! The authoring pipeline: every stage of a scene, in one order, each a pure function of its
//! inputs, recomputed only when those inputs change.
//!
//!   terrain -> placement -> control mesh -> fit -> tessellation -> layer base -> medium -> particles
//!                                                                         |          \-> light (baked)
//!                                                                         \-> exports (the layers an eye sees)
//!
//! A stage's inputs are a value (the options it reads, in world units, and the versions of the
//! stages it reads from) compared with a defaulted operator==; `run` redoes a stage only when its
//! inputs differ from those of its last run, and counts what it redid. `kiri author`, `kiri
//! render`, `kiri bench` and the preview's worker thread all drive this one object; the preview
//! adds only its thread (docs/architecture.md).
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "kiri/geometry/fog/base_surface.hpp"
#include "kiri/geometry/fog/tessellate.hpp"
#include "kiri/geometry/layers/layer_stack.hpp"
#include "kiri/geometry/medium/light_volume.hpp"
#include "kiri/geometry/medium/medium.hpp"
#include "kiri/geometry/particles/particles.hpp"
#include "kiri/geometry/placement/fog_placement.hpp"
#include "kiri/geometry/scene/fog_spec.hpp"
#include "kiri/geometry/scene/scene.hpp"
#include "kiri/geometry/scene/scene_defaults.hpp"
#include "kiri/geometry/terrain/terrain.hpp"

namespace kiri::geometry {

enum class Stage { terrain, placement, control_mesh, fit, tessellation, layer_base, medium, particles, light, exports };
inline constexpr int stage_count = 10;
//! "terrain", "placement", "control mesh", "fit", "tessellation", "layer base", "medium",
//! "particles", "light", "exports". The light stage bakes the light-transport volume
//! (light_volume_bake.hpp) for the Medium's model `baked` only; for the others it is skipped.
const char* to_string(Stage stage);

//! Which particles the particles stage samples.
enum class ParticleSet {
    none,      //!< no particles (the stage is skipped)
    whole,     //!< the whole Medium (`kiri render --mode particles`, `kiri author`)
    top_band,  //!< the particles' share of the Medium in combined rendering (fog_partition.hpp)
};

//! How far a run goes, and what the view-dependent stages are made for.
struct PipelineTarget {
    Stage up_to = Stage::layer_base;
    ParticleSet particles = ParticleSet::whole;  //!< when up_to reaches the particles
    glm::dvec3 export_eye{0.0};                  //!< exports: the eye the layers are built for
    //! The light stage, when up_to reaches it (and the Medium's model is `baked`): renderers
    //! need the light volume, `kiri author` does not.
    bool light = true;
    bool operator==(const PipelineTarget&) const = default;
};

//! The fitted base surface in figures (the surface itself stays in the Pipeline).
struct SurfaceSummary {
    FitReport fit;
    SurfaceKind kind = SurfaceKind::catmull_clark;
    int patches = 0, control_vertices = 0, snapped_boundary_vertices = 0, boundary_vertices = 0;
};

//! What a run made. Every part is immutable once made and shared, so another thread may hold
//! it while the pipeline works on; a part is null when the run did not reach its stage, or the
//! scene has no fog section (then only the terrain is set).
struct PipelineProducts {
    std::shared_ptr<const Terrain> terrain;
    //! The scene as the stages saw it: the run's scene with the keys it left out derived from
    //! the terrain (scene_defaults.hpp), and what was derived. Set whenever `terrain` is.
    std::shared_ptr<const Scene> scene;
    std::shared_ptr<const DerivedDefaults> derived;
    //! The fog section in world units, with the placed footprint and lake target (fog placed by
    //! the terrain), and the layer options as the stack is built and drawn (thickness and base
    //! offset set by the fog). Valid when `layer_base` is set.
    FogSpec fog;
    LayerOptions layers;
    std::shared_ptr<const PlacedFog> placed;  //!< fog placed by the terrain, else null
    std::shared_ptr<const SurfaceSummary> surface;
    std::shared_ptr<const Tessellation> tessellation;
    std::shared_ptr<const LayerBase> layer_base;
    std::shared_ptr<const Medium> medium;
    std::shared_ptr<const ParticleCloud> particles;  //!< null for ParticleSet::none or no share
    //! The baked multiple scattering of the Medium under the scene's sun (null unless the
    //! Medium's model is `baked` and the run reached the light stage), for every renderer.
    std::shared_ptr<const LightVolume> light_volume;
    std::shared_ptr<const std::vector<LayerMesh>> exports;  //!< every layer for the export eye
    bool has_fog() const { return layer_base != nullptr; }
};

struct StageRecord {
    int runs = 0;          //!< times the stage was computed
    double seconds = 0.0;  //!< wall time of its last computation
};

class Pipeline {
public:
    //! Told when a stage starts (done = false) and ends (done = true); the products made so far
    //! are products() (the preview shows a new terrain before its fog is fitted).
    using Observer = std::function<void(Stage stage, bool done)>;

    Pipeline();
    ~Pipeline();
    Pipeline(const Pipeline&) = delete;
    Pipeline& operator=(const Pipeline&) = delete;

    void set_observer(Observer observer) { observer_ = std::move(observer); }

    //! Brings the products up to date with `scene` as far as `target` says: only the stages whose
    //! inputs changed run. \throw InputError (naming the scene file) from the stage that failed;
    //! that stage then runs again next time, and the products keep what the last good runs made.
    const PipelineProducts& run(const Scene& scene, const PipelineTarget& target = {});

    const PipelineProducts& products() const { return products_; }
    //! The stage that threw in the last run, if any.
    std::optional<Stage> failed_stage() const { return failed_; }
    const std::array<StageRecord, stage_count>& stages() const { return records_; }
    //! Whether the last run computed `stage` (false: it was up to date, or not reached).
    bool ran(Stage stage) const { return ran_[std::size_t(stage)]; }
    //! The fitted base surface of the last good fit (null before): for views of the surface on
    //! the thread that runs the pipeline; the next run may change it.
    const BaseSurface* surface() const;

private:
    struct Cache;  // each stage's last inputs, version and product
    std::unique_ptr<Cache> cache_;
    PipelineProducts products_;
    std::array<StageRecord, stage_count> records_{};
    std::array<bool, stage_count> ran_{};
    std::optional<Stage> failed_;
    Observer observer_;

    void publish(const PipelineTarget& target);
};

//! The layer stack's options for a scene's fog: the scene's in world units, as deep as fog placed
//! by the terrain (`spec` is world_fog_spec with the placement applied, placed_fog_spec), and
//! for a lake hanging one thickness below the fitted top. \throw InputError naming /layers.
LayerOptions fog_layer_options(const Scene& scene, const FogSpec& spec);

//! Runs a fresh Pipeline once: the products of `scene` up to `target`.
PipelineProducts author_scene(const Scene& scene, const PipelineTarget& target = {});

}  // namespace kiri::geometry
