// Bench stages of the fog base-surface fit (docs/fog.md).
#include <cstdio>
#include <string>

#include "bench/bench.hpp"
#include "kiri/geometry/fog/base_surface.hpp"
#include "kiri/geometry/terrain/dem.hpp"

namespace {
using namespace kiri::geometry;

Heightfield jacksboro(const kiri::bench::Context& c)
{
    return load_dem(c.data_dir() / "terrains" / "jacksboro_fault_dem.tif");
}

Footprint inner_footprint(const Heightfield& hf, double margin)
{
    return rectangle_footprint({hf.x0 + margin, hf.y0 + margin}, {hf.x_max() - margin, hf.y_max() - margin});
}

std::string figures(const FitReport& r)
{
    char s[200];
    std::snprintf(s, sizeof s, "max_dev=%.2fm rms=%.2fm min_clear=%.3fm active=%lld iters=%d K=%d", r.max_deviation,
                  r.rms_deviation, r.min_clearance, r.active_constraints, r.iterations, r.samples_per_patch);
    return s;
}

// 2. Patch size against deviation from the target, clearance and time (default options,
//    blanket mode, the whole DEM less a 500 m margin).
KIRI_BENCH_STAGE({"fit",
                  "Jacksboro blanket fit: patch size vs RMS deviation",
                  {"patch size (m)", "error_value", "RMS deviation from target (m)", true, true},
                  [](kiri::bench::Context& c) {
                      const Terrain terrain(jacksboro(c));
                      const Footprint fp = inner_footprint(terrain.heightfield(), 500.0);
                      for (auto kind : {SurfaceKind::catmull_clark, SurfaceKind::gregory}) {
                          for (double patch : {250.0, 500.0, 1000.0, 2000.0}) {
                              if (c.quick() && patch < 500.0)
                                  continue;
                              FitReport rep;
                              std::size_t patches = 0;
                              const auto m = c.measure([&] {
                                  BaseSurface s(build_control_mesh(fp, terrain, {patch}), kind);
                                  rep = s.fit(terrain, {});
                                  patches = s.num_patches();
                              });
                              c.add({to_string(kind),
                                     "patch=" + std::to_string(int(patch)) + "m patches=" + std::to_string(patches) +
                                         " " + figures(rep),
                                     patch, m.seconds, "rms deviation (m)", rep.rms_deviation,
                                     double(rep.samples) / m.seconds, m.peak_rss_mb});
                          }
                      }
                  }});

// 3. Growth: the DEM resampled from 256^2 to 4096^2 samples, same extent and footprint, the
//    default fit (1000 m patches, one sample per cell); time and peak memory.
KIRI_BENCH_STAGE({"fit_growth",
                  "Fit cost growth with DEM size (Jacksboro resampled)",
                  {"DEM samples", "time_s", "time (s)", true, true},
                  [](kiri::bench::Context& c) {
                      const Heightfield source = jacksboro(c);
                      for (int n : {256, 512, 1024, 2048, 4096}) {
                          if (c.quick() && n > 1024)
                              break;
                          const Terrain terrain(resample(source, n, n));
                          const Footprint fp = inner_footprint(terrain.heightfield(), 500.0);
                          FitReport rep;
                          const auto m = c.measure([&] {
                              BaseSurface s(build_control_mesh(fp, terrain, {1000.0}), SurfaceKind::catmull_clark);
                              rep = s.fit(terrain, {});
                          });
                          c.add({"catmull-clark", "dem=" + std::to_string(n) + "^2 " + figures(rep), double(n) * n,
                                 m.seconds, "rms deviation (m)", rep.rms_deviation, double(rep.samples) / m.seconds,
                                 m.peak_rss_mb});
                      }
                  }});
}  // namespace
