#include "scene_worker.hpp"

#include <exception>

namespace kiri::preview {
namespace {

bool same_terrain(const geometry::TerrainSpec& a, const geometry::TerrainSpec& b)
{
    return a.path == b.path && a.exaggeration == b.exaggeration && a.cell_size == b.cell_size &&
           a.vertical_scale == b.vertical_scale && a.vertical_offset == b.vertical_offset;
}

// The fog section and the layer options that shape the base (texture); the rest of the layer
// options apply per frame without a rebuild.
std::string fog_key(const geometry::Scene& s)
{
    geometry::Scene copy;
    copy.terrain = s.terrain;
    copy.fog = s.fog;
    copy.layers.count = s.layers.count;
    copy.layers.texture = s.layers.texture;
    return geometry::scene_to_json(copy);
}

double since(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

SceneState compute(geometry::Scene scene, SceneState previous)
{
    SceneState out;
    out.scene = scene;
    try {
        auto t0 = std::chrono::steady_clock::now();
        if (previous.terrain && same_terrain(previous.scene.terrain, scene.terrain)) {
            out.terrain = previous.terrain;
        } else {
            out.terrain = std::make_shared<const geometry::Terrain>(geometry::load_scene_terrain(scene));
            out.terrain_rebuilt = true;
            out.terrain_seconds = since(t0);
        }
        if (!scene.fog)
            return out;
        if (!out.terrain_rebuilt && previous.fog && fog_key(previous.scene) == fog_key(scene)) {
            out.fog = previous.fog;
            return out;
        }
        t0 = std::chrono::steady_clock::now();
        out.fog = std::make_shared<const geometry::SceneFog>(geometry::author_scene_fog(scene, *out.terrain));
        out.fog_rebuilt = true;
        out.fog_seconds = since(t0);
    } catch (const std::exception& e) {
        out.error = e.what();
        if (!out.terrain)
            out.terrain = previous.terrain;
        out.fog = previous.fog;
        out.scene = previous.scene;
    }
    return out;
}

}  // namespace

void SceneWorker::start(Job job)
{
    started_ = std::chrono::steady_clock::now();
    running_ = std::async(std::launch::async, compute, std::move(job.scene), std::move(job.previous));
}

void SceneWorker::request(const geometry::Scene& scene, const SceneState& previous)
{
    Job job{scene, previous};
    if (running_.valid())
        pending_ = std::move(job);  // latest wins
    else
        start(std::move(job));
}

std::optional<SceneState> SceneWorker::poll()
{
    if (!running_.valid() || running_.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
        return std::nullopt;
    SceneState done = running_.get();
    if (pending_) {
        Job next = std::move(*pending_);
        pending_.reset();
        next.previous = done;  // build on what just finished
        start(std::move(next));
    }
    return done;
}

std::optional<SceneState> SceneWorker::wait()
{
    std::optional<SceneState> last;
    while (running_.valid()) {
        running_.wait();
        if (auto s = poll())
            last = std::move(s);
    }
    return last;
}

double SceneWorker::running_seconds() const { return running_.valid() ? since(started_) : 0.0; }

}  // namespace kiri::preview
