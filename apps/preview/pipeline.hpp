#pragma once
// The preview's recomputation, off the render thread. A scene goes through stages, each
// redone only when its inputs changed (compared as the JSON of the scene's parts it reads):
//
//   terrain (file, exaggeration) -> placement (fog placed by the terrain: fill, outline, flow,
//     burn-off) -> control mesh (footprint, patch size, surface kind) -> fit (fit options)
//     -> tessellation -> layer base (texture) + views (overlay meshes)
//     -> medium (the optics, the layers' detail) -> particles (the sampling options)
//
// The medium and the particles are made only when the window's render mode asks for them
// (Needs): a scene shown as layers never pays the ~1 s of sampling 60k particles.
//
// One worker thread runs one job at a time; a request made while it works replaces any
// waiting one (the latest edit wins) and the running job finishes, so a slider dragged for
// a while still shows intermediate results. Jobs are numbered (generations): the window knows
// whether what it shows is the latest edit.
#include <array>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "fog_views.hpp"
#include "kiri/geometry/medium/medium.hpp"
#include "kiri/geometry/particles/particles.hpp"
#include "kiri/geometry/scene/scene.hpp"
#include "kiri/geometry/terrain/terrain.hpp"

namespace kiri::preview {

enum class Stage { terrain, placement, control_mesh, fit, tessellation, layer_base, views, medium, particles };
inline constexpr int stage_count = 9;
const char* stage_name(Stage stage);

struct StageRecord {
    int runs = 0;
    double last_seconds = 0.0;
};

//! What one job produced: the terrain and, when the scene has a fog section that worked, the
//! fog. Shared read-only with the render thread. A job hands out its terrain as soon as it is
//! loaded (with the fog it had before), then the whole.
struct Products {
    std::uint64_t generation = 0;
    geometry::Scene scene;  //!< the scene these come from
    std::shared_ptr<const geometry::Terrain> terrain;
    std::shared_ptr<const FogProducts> fog;  //!< null: no fog section (or it never worked)
    //! The fog as a participating medium and as particles: null unless the request needed them.
    std::shared_ptr<const geometry::Medium> medium;
    std::shared_ptr<const geometry::ParticleCloud> particles;
    std::string error;  //!< one line; the products are then the last good ones
    std::array<bool, stage_count> rebuilt{};
};

struct PipelineStatus {
    bool busy = false;
    Stage stage = Stage::terrain;  //!< running now (when busy)
    double stage_seconds = 0.0, job_seconds = 0.0;
    std::uint64_t requested = 0, finished = 0;
    std::array<StageRecord, stage_count> stages{};
};

//! What the window's render mode draws beyond the layers (the stages after the views).
struct Needs {
    bool medium = false;     //!< froxel fog, or the particles' source
    bool particles = false;  //!< implies the medium
    //! Combined rendering: the particles stand for their share of the Medium only (the top
    //! band, the scene's "combined" section; render/scene_rendering.hpp); none when it is 0.
    bool particle_share = false;
    bool operator==(const Needs&) const = default;
};

class Pipeline {
public:
    Pipeline();
    ~Pipeline();  // waits for the running stage, then stops
    Pipeline(const Pipeline&) = delete;
    Pipeline& operator=(const Pipeline&) = delete;

    //! Queues `scene`; returns its generation.
    std::uint64_t request(const geometry::Scene& scene, Needs needs = {});
    //! The newest finished job not taken yet.
    std::optional<Products> take();
    //! Blocks until every request so far has finished.
    void wait_idle();
    PipelineStatus status() const;

private:
    struct Cache;  // the worker's own state (stage keys, the fitted surface): worker thread only
    std::unique_ptr<Cache> cache_;

    mutable std::mutex mutex_;
    std::condition_variable wake_, idle_;
    bool stop_ = false;
    std::optional<geometry::Scene> pending_;
    Needs pending_needs_;
    std::optional<Products> result_;
    PipelineStatus status_;
    std::chrono::steady_clock::time_point job_start_, stage_start_;
    std::thread worker_;  // last: starts once the rest is built

    void run();
    Products compute(const geometry::Scene& scene, Needs needs, std::uint64_t generation);
    //! Hands out what a job has so far (the terrain before the fog is fitted).
    void publish_partial(const Products& partial);
    void enter(Stage stage);
    void leave(Stage stage);
};

}  // namespace kiri::preview
