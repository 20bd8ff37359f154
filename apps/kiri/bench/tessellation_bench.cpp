// Bench stage of the base-surface tessellation: triangles against the
// maximum distance to the exact surface, uniform levels and adaptive tolerances.
#include <cstdio>
#include <string>

#include "bench/bench.hpp"
#include "kiri/geometry/fog/base_surface.hpp"
#include "kiri/geometry/terrain/dem.hpp"
#include "kiri/geometry/fog/tessellate.hpp"

namespace {
using namespace kiri::geometry;

KIRI_BENCH_STAGE(
    {"tessellation",
     "Base surface tessellation: triangles vs max distance to the surface",
     {"triangles", "error_value", "max |S(u,v) - triangle| (m)", true, true},
     [](kiri::bench::Context& c) {
         const Terrain terrain(load_dem(c.data_dir() / "terrains" / "jacksboro_fault_dem.tif"));
         const Heightfield& hf = terrain.heightfield();
         const Footprint fp = rectangle_footprint({hf.x0 + 500, hf.y0 + 500}, {hf.x_max() - 500, hf.y_max() - 500});
         BaseSurface s(build_control_mesh(fp, terrain, {1000.0}), SurfaceKind::catmull_clark);
         s.fit(terrain, {});
         for (int level : {1, 2, 4, 8, 16, 32}) {
             if (c.quick() && level > 16)
                 break;
             Tessellation t;
             const auto m = c.measure([&] { t = tessellate(s, {level}); });
             c.add({"uniform", "level=" + std::to_string(level), double(t.mesh.n_faces()), m.seconds,
                    "max distance (m)", t.max_error, double(t.mesh.n_faces()) / m.seconds, m.peak_rss_mb});
         }
         for (double tol : {10.0, 3.0, 1.0, 0.3, 0.1}) {
             if (c.quick() && tol < 0.3)
                 break;
             Tessellation t;
             const auto m = c.measure([&] { t = tessellate(s, {8, tol, 128}); });
             char label[64];
             std::snprintf(label, sizeof label, "tolerance=%gm", tol);
             c.add({"adaptive", label, double(t.mesh.n_faces()), m.seconds, "max distance (m)", t.max_error,
                    double(t.mesh.n_faces()) / m.seconds, m.peak_rss_mb});
         }
     }});
}  // namespace
