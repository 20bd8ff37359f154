// Bench stage "surface": batch evaluation of Gregory patches (position + exact first
// derivatives) by kiri's vectorised evaluate_into against OpenSubdiv evaluating the same
// patches (its GREGORY_BASIS patch basis, as PatchTable::EvaluateBasis does, then the
// weighted sum of the 20 points), side by side at several batch sizes. Error column: the
// largest position difference between the two over every evaluated point. Second pair of
// series: the Surface interface on a regular grid, Gregory network vs OpenSubdiv's Bfr limit
// (the same bicubic B-spline surface there).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "bench/bench.hpp"
#include "kiri/geometry/surface/gregory_opensubdiv.hpp"
#include "kiri/geometry/surface/gregory_patch.hpp"
#include "kiri/geometry/terrain/mesh.hpp"
#include "kiri/geometry/surface/surface.hpp"

namespace {

using kiri::bench::Context;
using kiri::bench::Row;
using namespace kiri::geometry;

// Patches of a G1 network over a bumpy quad mesh with a valence-5 vertex: genuine Gregory
// patches (distinct interior pairs), about 100 m each.
std::vector<GregoryPatch> network_patches()
{
    PolyMesh m;
    const int n = 5;
    const auto c = m.add_vertex(PolyMesh::Point(0, 0, 0));
    std::vector<PolyMesh::VertexHandle> ring, outer;
    for (int k = 0; k < 2 * n; ++k) {
        const double a = M_PI * k / n;
        ring.push_back(m.add_vertex(PolyMesh::Point(100 * std::cos(a), 100 * std::sin(a), 0)));
        outer.push_back(m.add_vertex(PolyMesh::Point(200 * std::cos(a), 200 * std::sin(a), 0)));
    }
    for (int k = 0; k < n; ++k)
        m.add_face(std::vector<PolyMesh::VertexHandle>{c, ring[2 * k], ring[2 * k + 1], ring[(2 * k + 2) % (2 * n)]});
    for (int k = 0; k < 2 * n; ++k)
        m.add_face(
            std::vector<PolyMesh::VertexHandle>{ring[k], outer[k], outer[(k + 1) % (2 * n)], ring[(k + 1) % (2 * n)]});
    std::mt19937 rng(20261122);
    std::uniform_real_distribution<double> dz(-20.0, 20.0);
    for (auto v : m.vertices())
        m.set_point(v, m.point(v) + PolyMesh::Point(0.0, 0.0, 300.0 + dz(rng)));
    const auto s = make_surface(m, SurfaceKind::gregory);
    std::vector<GregoryPatch> out;
    for (int f = 0; f < s->num_faces(); ++f)
        out.push_back(*s->gregory_patch(f));
    return out;
}

// On a regular grid the Gregory network is the bicubic B-spline, the same surface as
// OpenSubdiv's Catmull-Clark limit: both evaluated through kiri's Surface interface (the
// limit by Bfr::Surface::Evaluate on prepared patch points), same faces and points.
void run_regular_grid(Context& ctx, std::size_t batch, const std::vector<double>& u, const std::vector<double>& v,
                      std::size_t total)
{
    PolyMesh m;
    const int n = 8;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> dz(-20.0, 20.0);
    std::vector<PolyMesh::VertexHandle> vh;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
            vh.push_back(m.add_vertex(PolyMesh::Point(100.0 * i, 100.0 * j, 300.0 + dz(rng))));
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const int a = j * (n + 1) + i;
            m.add_face(std::vector<PolyMesh::VertexHandle>{vh[a], vh[a + 1], vh[a + n + 2], vh[a + n + 1]});
        }
    const auto g = make_surface(m, SurfaceKind::gregory);
    const auto c = make_surface(m, SurfaceKind::catmull_clark);
    PatchSamples a, b;
    a.resize(batch, false);
    b.resize(batch, false);
    const std::size_t rounds = std::max<std::size_t>(1, total / batch);
    const double points = double(rounds) * double(batch);
    auto run = [&](const Surface& s, PatchSamples& out) {
        const PatchSampleSpans sp = out.spans();
        for (std::size_t r = 0; r < rounds; ++r)
            s.evaluate_into(int(r % std::size_t(s.num_faces())), u, v, sp);
    };
    const auto tg = ctx.measure([&] { run(*g, a); }, 3);
    const auto tc = ctx.measure([&] { run(*c, b); }, 3);
    double err = 0.0;
    for (int f = 0; f < g->num_faces(); ++f) {
        g->evaluate_into(f, u, v, a.spans());
        c->evaluate_into(f, u, v, b.spans());
        for (std::size_t i = 0; i < batch; ++i)
            err = std::max(err, std::hypot(a.px[i] - b.px[i], a.py[i] - b.py[i], a.pz[i] - b.pz[i]));
    }
    const double rg = points / tg.seconds, rc = points / tc.seconds;
    char ratio[64];
    std::snprintf(ratio, sizeof ratio, " speedup=%.2fx", rg / rc);
    const std::string params = "batch=" + std::to_string(batch) + " grid=8x8";
    ctx.add(Row{"kiri surface gregory (regular grid)", params + ratio, double(batch), tg.seconds,
                "max |p_gregory - p_limit| (m)", err, rg, tg.peak_rss_mb});
    ctx.add(Row{"opensubdiv Bfr limit (regular grid)", params, double(batch), tc.seconds,
                "max |p_gregory - p_limit| (m)", err, rc, tc.peak_rss_mb});
}

void run_surface(Context& ctx)
{
    const std::vector<GregoryPatch> patches = network_patches();
    const std::size_t total = ctx.quick() ? (1u << 19) : (1u << 22);  // points per measurement
    const std::size_t max_batch = ctx.quick() ? (1u << 14) : (1u << 18);
    for (std::size_t batch = 16; batch <= max_batch; batch *= 8) {
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> d(0.0, 1.0);
        std::vector<double> u(batch), v(batch);
        for (std::size_t i = 0; i < batch; ++i) {
            u[i] = d(rng);
            v[i] = d(rng);
        }
        PatchSamples a, b;
        a.resize(batch, false);
        b.resize(batch, false);
        const std::size_t rounds = std::max<std::size_t>(1, total / batch);
        const double points = double(rounds) * double(batch);
        auto run = [&](PatchSamples& out, bool osd) {
            const PatchSampleSpans sp = out.spans();
            for (std::size_t r = 0; r < rounds; ++r) {
                const GregoryPatch& p = patches[r % patches.size()];
                if (osd)
                    evaluate_into_opensubdiv(p, u, v, sp);
                else
                    evaluate_into(p, u, v, sp);
            }
        };
        const auto tk = ctx.measure([&] { run(a, false); }, 5);
        const auto to = ctx.measure([&] { run(b, true); }, 5);
        // Error: every patch once at this batch's points, both ways.
        double err = 0.0;
        for (const auto& p : patches) {
            evaluate_into(p, u, v, a.spans());
            evaluate_into_opensubdiv(p, u, v, b.spans());
            for (std::size_t i = 0; i < batch; ++i)
                err = std::max(err, std::hypot(a.px[i] - b.px[i], a.py[i] - b.py[i], a.pz[i] - b.pz[i]));
        }
        const double rk = points / tk.seconds, ro = points / to.seconds;
        char ratio[64];
        std::snprintf(ratio, sizeof ratio, " speedup=%.2fx", rk / ro);
        const std::string params = "batch=" + std::to_string(batch) + " patches=" + std::to_string(patches.size());
        ctx.add(Row{"kiri gregory evaluate_into", params + ratio, double(batch), tk.seconds, "max |p_kiri - p_osd| (m)",
                    err, rk, tk.peak_rss_mb});
        ctx.add(Row{"opensubdiv GREGORY_BASIS", params, double(batch), to.seconds, "max |p_kiri - p_osd| (m)", err, ro,
                    to.peak_rss_mb});
        run_regular_grid(ctx, batch, u, v, total / 4);
    }
}

KIRI_BENCH_STAGE({"surface",
                  "Gregory patch batch evaluation (position + du, dv): kiri vs OpenSubdiv",
                  {"batch size (points)", "items_per_s", "points / s", true, true},
                  run_surface});

}  // namespace
