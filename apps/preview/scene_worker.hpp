#pragma once
// Recomputes what a scene edit invalidates (the terrain when its file or exaggeration changed,
// the fog's fit, tessellation and layer base when the fog or layer texture changed) on a
// background thread, so the window never freezes. Latest request wins; one job at a time.
#include <chrono>
#include <future>
#include <memory>
#include <optional>
#include <string>

#include "kiri/geometry/scene.hpp"
#include "kiri/geometry/scene_fog.hpp"
#include "kiri/geometry/terrain.hpp"

namespace kiri::preview {

struct SceneState {
    geometry::Scene scene;
    std::shared_ptr<const geometry::Terrain> terrain;
    std::shared_ptr<const geometry::SceneFog> fog;  // null when the scene has no fog or it failed
    double terrain_seconds = 0.0, fog_seconds = 0.0;
    bool terrain_rebuilt = false, fog_rebuilt = false;
    std::string error;  // one line, empty when all went well
};

class SceneWorker {
public:
    //! Queues a recomputation of `scene`. `previous` holds what is on screen: its terrain is
    //! reused when the terrain section is unchanged, its fog when fog and layer texture are.
    void request(const geometry::Scene& scene, const SceneState& previous);
    bool busy() const { return running_.valid() || pending_.has_value(); }
    //! The finished state, if any (starts the pending request, if any).
    std::optional<SceneState> poll();
    //! Blocks until nothing is queued or running; returns the last finished state.
    std::optional<SceneState> wait();
    //! Seconds the running job has taken so far (progress indicator).
    double running_seconds() const;

private:
    struct Job {
        geometry::Scene scene;
        SceneState previous;
    };
    std::future<SceneState> running_;
    std::optional<Job> pending_;
    std::chrono::steady_clock::time_point started_;
    void start(Job job);
};

}  // namespace kiri::preview
