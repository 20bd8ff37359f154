#include "pipeline.hpp"

#include <exception>
#include <utility>

namespace kiri::preview {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_between(Clock::time_point a, Clock::time_point b)
{
    return std::chrono::duration<double>(b - a).count();
}

}  // namespace

const char* stage_name(int stage)
{
    return stage == views_stage ? "views" : geometry::to_string(geometry::Stage(stage));
}

Pipeline::Pipeline() : worker_([this] { run(); }) {}

Pipeline::~Pipeline()
{
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    worker_.join();
}

std::uint64_t Pipeline::request(const geometry::Scene& scene, const geometry::PipelineTarget& target)
{
    std::uint64_t generation = 0;
    {
        std::lock_guard lock(mutex_);
        pending_ = scene;
        pending_target_ = target;
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
    s.waiting = result_.has_value();
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
        geometry::PipelineTarget target;
        std::uint64_t generation = 0;
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [this] { return stop_ || pending_.has_value(); });
            if (stop_)
                return;
            scene = std::move(*pending_);
            target = pending_target_;
            pending_.reset();
            generation = status_.requested;
            status_.busy = true;
            job_start_ = stage_start_ = Clock::now();
        }
        Products products = compute(scene, target, generation);
        {
            std::lock_guard lock(mutex_);
            result_ = std::move(products);
            status_.finished = generation;
            status_.busy = pending_.has_value();
        }
        idle_.notify_all();
    }
}

void Pipeline::enter(int stage)
{
    std::lock_guard lock(mutex_);
    status_.stage = stage;
    stage_start_ = Clock::now();
}

void Pipeline::leave(int stage)
{
    std::lock_guard lock(mutex_);
    StageRecord& r = status_.stages[std::size_t(stage)];
    ++r.runs;
    r.last_seconds = seconds_between(stage_start_, Clock::now());
}

Products Pipeline::compute(const geometry::Scene& scene, const geometry::PipelineTarget& target,
                           std::uint64_t generation)
{
    Products out;
    out.generation = generation;
    out.scene = scene;
    pipeline_.set_observer([&](geometry::Stage stage, bool done) {
        if (!done) {
            enter(int(stage));
            return;
        }
        leave(int(stage));
        out.rebuilt[std::size_t(stage)] = true;
        if (stage == geometry::Stage::terrain && scene.fog) {
            // The new terrain at once, with the old fog over it until the fit is done.
            Products partial = out;
            partial.fog = pipeline_.products();
            partial.views = views_;
            std::lock_guard lock(mutex_);
            result_ = std::move(partial);
        }
    });
    try {
        pipeline_.run(scene, target);
    } catch (const std::exception& e) {
        const std::optional<geometry::Stage> failed = pipeline_.failed_stage();
        out.error = std::string(failed ? geometry::to_string(*failed) : "scene") + ": " + e.what();
    }
    out.fog = pipeline_.products();
    if (!out.fog.has_fog()) {
        views_.reset();
        views_of_.reset();
    } else if (out.fog.tessellation != views_of_ && pipeline_.surface()) {
        enter(views_stage);
        views_ = make_fog_views(*pipeline_.surface(), *out.fog.tessellation, *out.fog.terrain, out.fog.fog.fit);
        views_of_ = out.fog.tessellation;
        leave(views_stage);
        out.rebuilt[views_stage] = true;
    }
    out.views = views_;
    return out;
}

}  // namespace kiri::preview
