// End to end: `kiri render` of the default scene from a cold start (a new process: loading
// the DEM, creating the GL context, compiling shaders, rendering, writing the PNG).
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

#include "bench/bench.hpp"
#include "kiri/geometry/core/error.hpp"

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
    for (const auto& [w, h] : sizes) {
        const ChildRun run =
            run_kiri({"render", scene, "-o", png, "--width", std::to_string(w), "--height", std::to_string(h)});
        Row row;
        row.series = "kiri render (cold start)";
        row.parameters = std::to_string(w) + "x" + std::to_string(h);
        row.x = double(w) * h;
        row.time_s = run.seconds;
        row.peak_rss_mb = run.peak_rss_mb;
        c.add(row);
    }
}

}  // namespace

KIRI_BENCH_STAGE({"end_to_end",
                  "kiri render of the default scene, cold start to PNG",
                  {"pixels", "time_s", "time (s)", true, false},
                  end_to_end});

}  // namespace kiri::bench
