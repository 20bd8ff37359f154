// Bench stage "outputs": `kiri author` of a bare DEM (every key derived from the terrain, the
// default formats) over DEM size: ~100 x 100 and 1201 x 1201 synthetic grids of 30 m cells, the
// bundled 403 x 344 DEM, and 3601 x 3601 (not in --quick). Each row: the wall time, the bytes
// written (the "error" column, in MiB) and the peak memory, beside the budgets of the issue
// "Any terrain a user brings" (docs/terrain.md): ~100 x 100 under 32 MiB, 5 s and 1 GiB; the
// bundled DEM under 64 MiB; 3601 x 3601 under 1 GiB, 60 s and 4 GiB.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "bench/bench.hpp"
#include "commands.hpp"

namespace {

namespace fs = std::filesystem;
using kiri::bench::Context;
using kiri::bench::Row;

// An ESRI ASCII grid of n x n cells of 30 m: rolling hills and a valley, 400..1600 m.
fs::path write_grid(const fs::path& dir, int n)
{
    const fs::path p = dir / ("hills_" + std::to_string(n) + ".asc");
    std::ofstream out(p);
    out << "ncols " << n << "\nnrows " << n << "\nxllcorner 500000\nyllcorner 4000000\ncellsize 30\n";
    char value[32];
    for (int j = 0; j < n; ++j) {
        const double y = double(j) / (n - 1);
        for (int i = 0; i < n; ++i) {
            const double x = double(i) / (n - 1);
            const double z = 800.0 + 300.0 * std::sin(9.0 * x) * std::sin(7.0 * y) +
                150.0 * std::cos(11.0 * y) * std::cos(13.0 * x) + 400.0 * y -
                300.0 * std::exp(-(x - 0.5) * (x - 0.5) / 0.004);
            std::snprintf(value, sizeof value, i + 1 < n ? "%.1f " : "%.1f\n", z);
            out << value;
        }
    }
    return p;
}

std::uintmax_t folder_bytes(const fs::path& dir)
{
    std::uintmax_t bytes = 0;
    std::error_code ec;
    for (const auto& e : fs::recursive_directory_iterator(dir, ec))
        if (e.is_regular_file())
            bytes += e.file_size();
    return bytes;
}

void measure(Context& c, const std::string& name, const fs::path& dem, double cells, double budget_mib)
{
    const fs::path out = c.out_dir() / ("outputs_" + name);
    fs::remove_all(out);
    const kiri::bench::Measured m = c.measure([&] { kiri::cli::run_author(dem.string(), out.string()); });
    Row row;
    row.series = "kiri author DEM";
    row.parameters = name + " (budget " + std::to_string(int(budget_mib)) + " MiB)";
    row.x = cells;
    row.time_s = m.seconds;
    row.error_metric = "output (MiB)";
    row.error_value = double(folder_bytes(out)) / 1048576.0;
    row.items_per_s = cells / std::max(m.seconds, 1e-9);
    row.peak_rss_mb = m.peak_rss_mb;
    c.add(row);
    std::fprintf(stderr, "outputs: %s: %.1f MiB in %.2f s, peak %.0f MB\n", name.c_str(), row.error_value, m.seconds,
                 m.peak_rss_mb);
    fs::remove_all(out);
}

KIRI_BENCH_STAGE({"outputs",
                  "kiri author of a bare DEM: output size, time and peak memory against the DEM's cells",
                  {"cells", "error_value", "output (MiB)", true, true, true},
                  [](Context& c) {
                      const fs::path dir = c.out_dir() / "outputs_dems";
                      fs::create_directories(dir);
                      measure(c, "100x100", write_grid(dir, 100), 1e4, 32);
                      measure(c, "jacksboro 403x344", c.data_dir() / "terrains/jacksboro_fault_dem.tif", 403.0 * 344,
                              64);
                      measure(c, "1201x1201", write_grid(dir, 1201), 1201.0 * 1201, 1024);
                      if (!c.quick())
                          measure(c, "3601x3601", write_grid(dir, 3601), 3601.0 * 3601, 1024);
                      fs::remove_all(dir);
                  }});

}  // namespace
