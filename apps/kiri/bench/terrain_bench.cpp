// Bench stage "terrain": the Jacksboro DEM resampled from 256^2 to 4096^2 (quick: to 1024^2);
// time and peak memory of load + resample, mesh build, AABB build and ray queries against the
// number of cells, each beside an error that says the result is right.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "bench/bench.hpp"
#include "kiri/geometry/terrain/dem.hpp"
#include "kiri/geometry/terrain/terrain.hpp"

namespace {

using kiri::bench::Context;
using kiri::bench::Row;
using kiri::geometry::Heightfield;
using kiri::geometry::Terrain;
using kiri::geometry::TriMesh;

// Random plan positions inside the grid (fixed seed: the same points at every size).
std::vector<glm::dvec2> random_points(const Heightfield& hf, int count)
{
    std::mt19937 rng(20261122);
    std::uniform_real_distribution<double> ux(hf.x0, hf.x_max()), uy(hf.y0, hf.y_max());
    std::vector<glm::dvec2> pts(count);
    for (auto& p : pts)
        p = {ux(rng), uy(rng)};
    return pts;
}

// Height of the mesh itself at (x, y): the face of the containing cell whose barycentric
// coordinates (from the mesh's own vertex positions) are all >= 0. Independent of
// Terrain::height(), which reads the heightfield.
std::optional<double> mesh_height(const TriMesh& mesh, const Heightfield& hf, double x, double y)
{
    const int ci = std::clamp(int((x - hf.x0) / hf.dx), 0, hf.nx - 2);
    const int cj = std::clamp(int((y - hf.y0) / hf.dy), 0, hf.ny - 2);
    const int cell = cj * (hf.nx - 1) + ci;
    for (int k = 0; k < 2; ++k) {
        const auto f = mesh.face_handle(2 * cell + k);
        OpenMesh::Vec3d p[3];
        int n = 0;
        for (const auto v : mesh.fv_range(f))
            p[n++] = mesh.point(v);
        const double det = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
        const double u = ((x - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (y - p[0][1])) / det;
        const double v = ((p[1][0] - p[0][0]) * (y - p[0][1]) - (x - p[0][0]) * (p[1][1] - p[0][1])) / det;
        if (u >= -1e-12 && v >= -1e-12 && u + v <= 1.0 + 1e-12)
            return p[0][2] + u * (p[1][2] - p[0][2]) + v * (p[2][2] - p[0][2]);
    }
    return std::nullopt;
}

void run_terrain(Context& ctx)
{
    const auto path = ctx.data_dir() / "terrains" / "jacksboro_fault_dem.tif";
    const Heightfield source = kiri::geometry::load_dem(path);
    const Terrain source_terrain(source);
    const int max_n = ctx.quick() ? 1024 : 4096;
    constexpr int kProbe = 20000;  // random points for the error columns

    for (int n = 256; n <= max_n; n *= 2) {
        const std::string params = "cells=" + std::to_string(n) + "^2";
        const double cells = double(n) * n;
        const auto probe = random_points(source, kProbe);

        // Load + resample: the error is how far the resampled terrain strays from the source
        // one (detail lost below the source's 403 x 344, interpolation above it).
        Heightfield hf;
        // Median of 3: the first call of the run also pays GDAL's driver registration.
        const auto load = ctx.measure([&] { hf = kiri::geometry::resample(kiri::geometry::load_dem(path), n, n); }, 3);
        double dev = 0.0;
        {
            const Terrain t(hf);
            for (const auto& p : probe)
                dev = std::max(dev, std::abs(t.height(p.x, p.y) - source_terrain.height(p.x, p.y)));
        }
        ctx.add(Row{"load+resample", params, cells, load.seconds, "max |h - h_source| (m)", dev, cells / load.seconds,
                    load.peak_rss_mb});

        // Mesh build, alone in its Terrain so the row's memory is the mesh's.
        {
            Terrain t(hf);
            const auto built = ctx.measure([&] { t.mesh(); });
            double err = 0.0;
            for (const auto& p : probe) {
                const auto z = mesh_height(t.mesh(), hf, p.x, p.y);
                err = std::max(err, z ? std::abs(*z - t.height(p.x, p.y)) : INFINITY);
            }
            ctx.add(Row{"mesh build", params, cells, built.seconds, "max |mesh(x,y) - height(x,y)| (m)", err,
                        cells / built.seconds, built.peak_rss_mb});
        }

        // AABB build (the first ray query builds it), then ray queries on the built tree.
        {
            Terrain t(hf);
            const glm::dvec3 down(0.0, 0.0, -1.0);
            const double top = t.bounds().max.z + 100.0;
            const auto built = ctx.measure([&] { t.intersect_ray({0.0, 0.0, top}, down); });
            double err = 0.0;
            int misses = 0;
            const auto rays = ctx.measure([&] {
                err = 0.0;
                misses = 0;
                for (const auto& p : probe) {
                    const auto hit = t.intersect_ray({p.x, p.y, top}, down);
                    if (!hit) {
                        ++misses;
                        continue;
                    }
                    err = std::max(err, std::abs(hit->point.z - t.height(p.x, p.y)));
                }
            });
            if (misses > 0)
                err = INFINITY;  // a vertical ray inside the grid must hit
            ctx.add(Row{"AABB build", params, cells, built.seconds, "max |ray hit z - height(x,y)| (m)", err,
                        cells / built.seconds, built.peak_rss_mb});
            ctx.add(Row{"20k vertical rays", params, cells, rays.seconds, "max |ray hit z - height(x,y)| (m)", err,
                        kProbe / rays.seconds, rays.peak_rss_mb});
        }
        std::printf("terrain %s done\n", params.c_str());
        std::fflush(stdout);
    }
}

KIRI_BENCH_STAGE({"terrain",
                  "Terrain: load + resample, mesh, AABB tree, rays (Jacksboro resampled)",
                  {"cells", "time_s", "time (s)", true, true},
                  run_terrain});

}  // namespace
