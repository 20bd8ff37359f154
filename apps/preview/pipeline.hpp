#pragma once
// The preview's worker thread around the authoring pipeline (geometry/scene/pipeline.hpp): the
// pipeline decides what a scene needs recomputed; this thread runs it off the render thread and
// adds the views of the fitted surface (tessellation, patch borders, control mesh, colour maps),
// made again whenever the tessellation is new.
//
// One job runs at a time; a request made while it works replaces any waiting one (the latest
// edit wins) and the running job finishes, so a slider dragged for a while still shows
// intermediate results. Jobs are numbered (generations): the window knows whether what it shows
// is the latest edit.
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
#include "kiri/geometry/scene/pipeline.hpp"

namespace kiri::preview {

//! The pipeline's stages, then the preview's own: the views of the fitted surface.
inline constexpr int views_stage = geometry::stage_count;
inline constexpr int stage_count = geometry::stage_count + 1;
const char* stage_name(int stage);

struct StageRecord {
    int runs = 0;
    double last_seconds = 0.0;
};

//! What one job produced. Shared read-only with the render thread. A job hands out its terrain
//! as soon as it is loaded (with the fog it had before), then the whole.
struct Products {
    std::uint64_t generation = 0;
    geometry::Scene scene;                  //!< the scene these come from
    geometry::PipelineProducts fog;         //!< the terrain, and the fog when the scene has one
    std::shared_ptr<const FogViews> views;  //!< of the fitted surface (null without fog)
    std::string error;                      //!< one line; the products are then the last good ones
    std::array<bool, stage_count> rebuilt{};
};

struct PipelineStatus {
    bool busy = false;
    int stage = 0;  //!< running now (when busy)
    double stage_seconds = 0.0, job_seconds = 0.0;
    std::uint64_t requested = 0, finished = 0;
    bool waiting = false;  //!< a finished job's products not taken yet
    std::array<StageRecord, stage_count> stages{};
};

class Pipeline {
public:
    Pipeline();
    ~Pipeline();  // waits for the running stage, then stops
    Pipeline(const Pipeline&) = delete;
    Pipeline& operator=(const Pipeline&) = delete;

    //! Queues `scene` with what its render mode needs; returns its generation.
    std::uint64_t request(const geometry::Scene& scene, const geometry::PipelineTarget& target);
    //! The newest finished job not taken yet.
    std::optional<Products> take();
    //! Blocks until every request so far has finished.
    void wait_idle();
    PipelineStatus status() const;

private:
    // Worker thread only: the pipeline and the views it last made.
    geometry::Pipeline pipeline_;
    std::shared_ptr<const FogViews> views_;
    std::shared_ptr<const geometry::Tessellation> views_of_;

    mutable std::mutex mutex_;
    std::condition_variable wake_, idle_;
    bool stop_ = false;
    std::optional<geometry::Scene> pending_;
    geometry::PipelineTarget pending_target_;
    std::optional<Products> result_;
    PipelineStatus status_;
    std::chrono::steady_clock::time_point job_start_, stage_start_;
    std::thread worker_;  // last: starts once the rest is built

    void run();
    Products compute(const geometry::Scene& scene, const geometry::PipelineTarget& target, std::uint64_t generation);
    void enter(int stage);
    void leave(int stage);
};

}  // namespace kiri::preview
