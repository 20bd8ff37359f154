// End to end: `kiri render` of the default scene from a cold start (a new process: loading
// the DEM, creating the GL context, compiling shaders, rendering, writing the PNG), and the
// error of the picture it wrote against the CPU reference: the PNG read back as radiance at the
// pixel centres of a 64 x 36 view (render::radiance_at), the fog judged as `kiri bench` judges
// every renderer (render::compare_frames, over the picture kiri render --mode terrain writes).
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include "bench/bench.hpp"
#include "bench/fog_judge.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/render/fog_error.hpp"
#include "kiri/render/image.hpp"
#include "kiri/render/tone_map.hpp"

namespace kiri::bench {
namespace {

struct ChildRun {
    double seconds = 0.0;
    double peak_rss_mb = 0.0;
};

ChildRun run_kiri(const std::vector<std::string>& args)
{
    std::vector<char*> argv;
    std::string self = "/proc/self/exe";
    argv.push_back(self.data());
    for (const std::string& a : args)
        argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = fork();
    if (pid == 0) {
        // The child's own messages would interleave with the bench table.
        if (FILE* null = std::fopen("/dev/null", "w")) {
            dup2(fileno(null), STDOUT_FILENO);
            dup2(fileno(null), STDERR_FILENO);
        }
        execv("/proc/self/exe", argv.data());
        _exit(127);
    }
    int status = 0;
    rusage usage{};
    wait4(pid, &status, 0, &usage);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        throw Error("bench end_to_end: kiri render failed (exit status " + std::to_string(WEXITSTATUS(status)) + ")");
    return {seconds, double(usage.ru_maxrss) / 1024.0};
}

void end_to_end(Context& c)
{
    const std::string scene = (c.data_dir() / "scenes/jacksboro.json").string();
    const std::string png = (c.out_dir() / "end_to_end_render.png").string();
    // --quick (the tests) keeps to small frames.
    std::vector<std::pair<int, int>> sizes = {{320, 180}, {640, 360}};
    if (!c.quick())
        sizes = {{640, 360}, {1280, 720}, {1920, 1080}};
    // The reference of the default view at 64 x 36, once; each size's picture is judged at it.
    const int judge_width = 64, judge_height = 36;
    const FogJudge judge(geometry::load_scene(scene), "", judge_width, judge_height);
    const std::string bare_png = (c.out_dir() / "end_to_end_bare.png").string();
    for (const auto& [w, h] : sizes) {
        const std::string width = std::to_string(w), height = std::to_string(h);
        const ChildRun run = run_kiri({"render", scene, "-o", png, "--width", width, "--height", height});
        run_kiri({"render", scene, "-o", bare_png, "--width", width, "--height", height, "--mode", "terrain"});
        const render::FogError error = render::compare_frames(
            render::radiance_at(render::read_png(png), judge_width, judge_height),
            render::radiance_at(render::read_png(bare_png), judge_width, judge_height), judge.reference());
        Row row;
        row.series = "kiri render (cold start)";
        row.parameters = width + "x" + height;
        row.x = double(w) * h;
        row.time_s = run.seconds;
        row.error_metric = "mean relative luminance error vs reference (64x36)";
        row.error_value = error.mean_relative;
        row.peak_rss_mb = run.peak_rss_mb;
        c.add(row);
    }
    std::filesystem::remove(bare_png);
}

}  // namespace

KIRI_BENCH_STAGE({"end_to_end",
                  "kiri render of the default scene, cold start to PNG, and its error",
                  {"pixels", "time_s", "time (s)", true, false},
                  end_to_end});

}  // namespace kiri::bench
