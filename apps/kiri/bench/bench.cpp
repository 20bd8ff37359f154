#include "bench/bench.hpp"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <string>

namespace kiri::bench {
namespace {

// Peak resident memory of this process since the last reset, in MiB (VmHWM).
double peak_rss_mb()
{
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);)
        if (line.rfind("VmHWM:", 0) == 0)
            return std::stod(line.substr(6)) / 1024.0;
    return 0.0;
}

// Writing "5" to clear_refs resets the peak RSS (Linux >= 4.0), so each measurement reports
// its own peak rather than the whole run's.
void reset_peak_rss()
{
    std::ofstream clear("/proc/self/clear_refs");
    clear << "5";
}

}  // namespace

Context::Context(std::filesystem::path out_dir, std::filesystem::path data_dir, bool quick,
                 std::vector<std::string> view_filter)
    : out_dir_(std::move(out_dir)), data_dir_(std::move(data_dir)), quick_(quick), view_filter_(std::move(view_filter))
{}

bool Context::wants_view(const std::string& label) const
{
    if (view_filter_.empty())
        return true;
    for (const std::string& text : view_filter_)
        if (label.find(text) != std::string::npos)
            return true;
    return false;
}

Measured Context::measure(const std::function<void()>& fn, int repeats)
{
    std::vector<double> times;
    double peak = 0.0;
    for (int k = 0; k < std::max(repeats, 1); ++k) {
        reset_peak_rss();
        const auto start = std::chrono::steady_clock::now();
        fn();
        times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        peak = std::max(peak, peak_rss_mb());
    }
    std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
    return {times[times.size() / 2], peak};
}

void Context::add(Row row) { rows_.push_back(std::move(row)); }

std::vector<Stage>& stages()
{
    static std::vector<Stage> all;
    return all;
}

bool register_stage(Stage stage)
{
    stages().push_back(std::move(stage));
    return true;
}

}  // namespace kiri::bench
