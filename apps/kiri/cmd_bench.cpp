// `kiri bench [--quick] -o DIR [--stage NAME ...] [--view TEXT ...]`: runs the benchmark stages; each writes
// DIR/<stage>.csv (time, error and peak memory per row) and DIR/<stage>.png.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "bench/bench.hpp"
#include "bench/report.hpp"
#include "commands.hpp"
#include "kiri/geometry/core/error.hpp"

namespace kiri::cli {
namespace {

struct BenchArgs {
    std::string out;
    std::vector<std::string> stages;
    std::vector<std::string> views;
    bool quick = false;
    bool list = false;
};

std::filesystem::path data_dir()
{
    // The source tree's data/ unless KIRI_DATA_DIR points elsewhere (an installed kiri).
    if (const char* env = std::getenv("KIRI_DATA_DIR"))
        return env;
    return KIRI_SOURCE_DATA_DIR;
}

void run(const BenchArgs& a)
{
    if (!KIRI_BUILD_BENCH)
        throw InputError("", "bench", "this kiri was built without its benchmark stages (KIRI_BUILD_BENCH=OFF)");
    auto& all = bench::stages();
    if (a.list) {
        for (const bench::Stage& s : all)
            std::printf("%-16s %s\n", s.name.c_str(), s.title.c_str());
        return;
    }
    if (a.out.empty())
        throw InputError("", "--out", "an output folder is required");
    std::set<std::string> known;
    for (const bench::Stage& s : all)
        known.insert(s.name);
    for (const std::string& s : a.stages)
        if (!known.count(s))
            throw InputError("", "--stage", "unknown stage \"" + s + "\" (see kiri bench --list)");
    if (!a.views.empty() && !a.stages.empty() && std::find(a.stages.begin(), a.stages.end(), "views") == a.stages.end())
        throw InputError("", "--view", "chooses views of the views stage, which is not run (add --stage views)");
    std::error_code ec;
    std::filesystem::create_directories(a.out, ec);
    if (ec || !std::filesystem::is_directory(a.out))
        throw IoError(a.out, "", "cannot create the output folder");
    check_output_file((std::filesystem::path(a.out) / "probe").string());
    const std::set<std::string> wanted(a.stages.begin(), a.stages.end());
    for (const bench::Stage& stage : all) {
        if (!wanted.empty() && !wanted.count(stage.name))
            continue;
        std::printf("== %s: %s\n", stage.name.c_str(), stage.title.c_str());
        std::fflush(stdout);
        bench::Context context(a.out, data_dir(), a.quick, a.views);
        stage.run(context);
        for (const bench::Row& r : context.rows()) {
            // Rows without an error metric leave the column empty rather than print a 0.
            char error[160] = "";
            if (!r.error_metric.empty())
                std::snprintf(error, sizeof error, "%s = %.3g", r.error_metric.c_str(), r.error_value);
            std::printf("  %-24s %-20s %10.4f s %9.1f MiB  %s\n", r.series.c_str(), r.parameters.c_str(), r.time_s,
                        r.peak_rss_mb, error);
        }
        const std::filesystem::path base = std::filesystem::path(a.out) / stage.name;
        bench::write_csv(base.string() + ".csv", stage, context.rows());
        const bool plotted = bench::write_plot(base.string() + ".png", stage, context.rows());
        std::printf("  -> %s.csv%s\n", base.c_str(), plotted ? (", " + base.string() + ".png").c_str() : "");
        std::fflush(stdout);
    }
}

}  // namespace

void add_bench_command(CLI::App& app)
{
    auto* sub = app.add_subcommand("bench", "Run the benchmark stages: CSV of time, error and memory, and a plot each");
    auto a = std::make_shared<BenchArgs>();
    sub->add_option("-o,--out", a->out, "output folder for the CSV files and plots");
    sub->add_option("--stage", a->stages, "run only these stages (repeatable)");
    sub->add_option("--view", a->views,
                    "the views stage: only the views whose label holds this text (repeatable; e.g. lake)");
    sub->add_flag("--quick", a->quick, "smaller sizes, for a quick look");
    sub->add_flag("--list", a->list, "list the stages and exit");
    sub->callback([a] { run(*a); });
}

}  // namespace kiri::cli
