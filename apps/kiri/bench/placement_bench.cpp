// Bench stages of fog placed by the terrain: "fill" (priority-flood fill of
// Jacksboro's SE valleys to 460 m, and the full flood levels from the same seed, against the
// DEM resampled from 256^2 to 4096^2; goal 4096^2 under 2 s) and "flow" (one flow step against
// the grid size). Each row has an error beside its time.
#include <cmath>
#include <cstdio>
#include <string>

#include "bench/bench.hpp"
#include "kiri/geometry/terrain/dem.hpp"
#include "kiri/geometry/placement/fog_columns.hpp"
#include "kiri/geometry/placement/fog_fill.hpp"
#include "kiri/geometry/placement/fog_flow.hpp"

namespace {

using namespace kiri::geometry;
using kiri::bench::Context;

const int kSizes[] = {256, 512, 1024, 2048, 4096};

Heightfield load_jacksboro(const Context& c) { return load_dem(c.data_dir() / "terrains" / "jacksboro_fault_dem.tif"); }

FillOptions valley_fill()
{
    FillOptions o;
    o.top = 460.0;
    o.seeds.points = {{11100.0, 6600.0}};
    return o;
}

std::string size_name(int n) { return "dem=" + std::to_string(n) + "^2"; }

KIRI_BENCH_STAGE({"fill",
                  "Priority-flood fill vs DEM size (Jacksboro resampled)",
                  {"DEM cells", "time_s", "time (s)", true, true},
                  [](Context& c) {
                      const Heightfield source = load_jacksboro(c);
                      // The native grid's fog area is the reference of the resampled ones.
                      const double reference = fill_fog(source, valley_fill()).area_m2;
                      for (int n : kSizes) {
                          if (c.quick() && n > 1024)
                              break;
                          const Heightfield hf = resample(source, n, n);
                          const double cells = double(n) * n;
                          FogFill f;
                          const auto m = c.measure([&] { f = fill_fog(hf, valley_fill()); }, n <= 1024 ? 3 : 1);
                          char p[160];
                          std::snprintf(p, sizeof p, "%s fog_cells=%zu area=%.1fkm2 spill=%.1fm", size_name(n).c_str(),
                                        f.cells, f.area_m2 * 1e-6, f.spill_level);
                          c.add({"fill to 460 m", p, cells, m.seconds, "|area / area(403x344) - 1|",
                                 std::abs(f.area_m2 / reference - 1.0), cells / m.seconds, m.peak_rss_mb});
                          FloodLevels levels;
                          const auto all =
                              c.measure([&] { levels = flood_levels(hf, valley_fill().seeds); }, n <= 1024 ? 3 : 1);
                          // Check: the fill is exactly the cells whose flood level is below the top.
                          std::size_t mismatch = 0;
                          for (std::size_t k = 0; k < hf.size(); ++k)
                              mismatch += (levels.reached[k] && levels.level[k] < 460.0) != (f.mask[k] != 0);
                          c.add({"flood levels (whole grid)", size_name(n), cells, all.seconds,
                                 "cells disagreeing with the fill", double(mismatch), cells / all.seconds,
                                 all.peak_rss_mb});
                      }
                  }});

KIRI_BENCH_STAGE({"flow",
                  "Flow step (pools + semi-Lagrangian stream) vs grid size",
                  {"DEM cells", "time_s", "time per step (s)", true, true},
                  [](Context& c) {
                      const Heightfield source = load_jacksboro(c);
                      for (int n : kSizes) {
                          if (c.quick() && n > 1024)
                              break;
                          const Heightfield hf = resample(source, n, n);
                          const FogColumns fog = fill_columns(hf, fill_fog(hf, valley_fill()));
                          FlowOptions o;
                          o.wind = {-3.0, 4.0};
                          o.evaporation_depth = 0.0;  // so the volume is an exact check
                          // The same physical step at every size: the stream crosses more cells as they shrink.
                          const double dt = 60.0;
                          FlowState st = make_flow_state(hf, fog, o);
                          double v0 = 0.0;
                          for (double h : flow_thickness(hf, st, o))
                              v0 += h * hf.dx * hf.dy;
                          const int steps = 5;
                          const auto m = c.measure([&] {
                              for (int s = 0; s < steps; ++s)
                                  flow_step(hf, st, o, dt);
                          });
                          double v = st.outflow_m3;
                          for (double h : flow_thickness(hf, st, o))
                              v += h * hf.dx * hf.dy;
                          char p[160];
                          std::snprintf(p, sizeof p, "%s dt=%.0fs pools=%zu spilled=%.3gm3", size_name(n).c_str(), dt,
                                        st.pools.size(), st.spilled_m3);
                          c.add({"flow step", p, double(n) * n, m.seconds / steps, "|volume / volume0 - 1|",
                                 std::abs(v / v0 - 1.0), double(n) * n * steps / m.seconds, m.peak_rss_mb});
                      }
                  }});

}  // namespace
