// The fit's steps after the first solve: the clearance (active set), the local and uniform
// lifts that guarantee it, and the figures of the report.
#include <algorithm>
#include <cmath>
#include <limits>

#include "fog/fit_solver.hpp"
#include "fog/fit_steps.hpp"

namespace kiri::geometry {

double surface_z(const FitLayout& layout, int face, const double* w, const std::vector<double>& heights)
{
    const auto& S = layout.stencils.support(face);
    double z = 0.0;
    for (std::size_t k = 0; k < S.size(); ++k)
        z += w[k] * heights[S[k]];
    return z;
}

// Each sample with data carries t >= 0 (its multiplier over the penalty, in metres); a sample
// is held, with a penalty rho (300 x a sample's data weight; stiffer penalties oscillate on
// Jacksboro) towards terrain + clearance + t, while t + (need - z) > 0, and after each solve t
// grows by what the sample still lacks. Raising the held targets rather than holding them at
// equality is what resolves conflicts between held samples (a peak narrower than a patch): the
// converged t are the constraint forces of the exact inequality-constrained least-squares
// problem (Uzawa). What is left after max_active_set_iterations goes to the lifts.
std::vector<double> enforce_clearance(const FitLayout& layout, const FitAssembly& assembly, const FitOptions& o,
                                      FitSolver& solver, std::vector<double> hts, long long& held)
{
    const double rho = 300.0, tol = 1e-3;
    const int nf = layout.num_faces();
    const FitSamples& smp = layout.samples;
    const SampleHeights& samples = assembly.samples;
    const std::vector<FaceSystem>& base = assembly.faces;
    std::vector<FaceSystem> sys = base;
    std::vector<float> raise(smp.uv.size(), 0.0f);
    std::vector<std::uint8_t> holding(smp.uv.size(), 0);
    // Samples far above their bound are skipped until the heights have moved enough to reach
    // them: a face's samples move by at most kStencilBound x the largest height change of its
    // support (the weights' absolute sum; 1 for B-spline patches).
    constexpr double kStencilBound = 2.0;
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<double> moved(nf, inf), min_slack(nf, -inf);
    // The one-step inner solves can cycle on hard terrains: keep the best iterate.
    std::vector<double> best = hts;
    double best_worst = inf;
    for (int it = 0; it < o.max_active_set_iterations; ++it) {
        long long count = 0;
        double worst = 0.0;
        for (int f = 0; f < nf; ++f) {
            sys[f] = base[f];
            const bool full = !(moved[f] < min_slack[f]);
            if (full) {
                moved[f] = 0.0;
                min_slack[f] = inf;
            }
            for (std::size_t id = smp.face_begin[f]; id < smp.face_begin[f + 1]; ++id) {
                if (!samples.has_data[id])
                    continue;
                const bool was = holding[id];
                if (!was && !full)
                    continue;
                const double* w = assembly.weights_of(layout, f, id);
                const double need = samples.terrain[id] + o.clearance, lack = need - surface_z(layout, f, w, hts);
                worst = std::max(worst, lack);
                if (was)
                    raise[id] = float(std::max(0.0, double(raise[id]) + lack));
                const bool hold = double(raise[id]) + lack > 0.0;
                holding[id] = hold;
                if (hold) {
                    add_row(sys[f], w, layout.stencils.support(f).size(), rho * assembly.data_weight[f],
                            need + double(raise[id]));
                    ++count;
                } else if (full) {
                    min_slack[f] = std::min(min_slack[f], -lack - double(raise[id]));
                }
            }
        }
        held = count;
        if (worst < best_worst) {
            best_worst = worst;
            best = hts;
        }
        if (worst <= tol)
            break;
        const std::vector<double> before = hts;
        hts = solver.solve(sys);
        for (int f = 0; f < nf; ++f) {
            double d = 0.0;
            for (int v : layout.stencils.support(f))
                d = std::max(d, std::abs(hts[v] - before[v]));
            moved[f] += kStencilBound * d;
        }
    }
    return best;  // (the last solve is unchecked: the loop ends on a check when it converges)
}

// The positive weights of a sample sum to >= 1, so raising the control vertices under it by
// its shortfall raises it at least that much; a few passes settle the interplay of neighbours.
double lift_locally(const FitLayout& layout, const FitAssembly& assembly, double clearance, std::vector<double>& hts)
{
    const int nf = layout.num_faces(), nv = layout.num_vertices();
    const FitSamples& smp = layout.samples;
    const SampleHeights& samples = assembly.samples;
    double largest = 0.0;
    for (int pass = 0; pass < 4; ++pass) {
        std::vector<double> up(nv, 0.0);
        double worst = 0.0;
        for (int f = 0; f < nf; ++f) {
            const auto& S = layout.stencils.support(f);
            for (std::size_t id = smp.face_begin[f]; id < smp.face_begin[f + 1]; ++id) {
                if (!samples.has_data[id])
                    continue;
                const double* w = assembly.weights_of(layout, f, id);
                const double lack = samples.terrain[id] + clearance - surface_z(layout, f, w, hts);
                if (lack <= 0.0)
                    continue;
                worst = std::max(worst, lack);
                for (std::size_t k = 0; k < S.size(); ++k)
                    if (w[k] > 1e-12)
                        up[S[k]] = std::max(up[S[k]], lack * (1.0 + 1e-9));
            }
        }
        if (worst == 0.0)
            break;
        for (int v = 0; v < nv; ++v) {
            hts[v] += up[v];
            largest = std::max(largest, up[v]);
        }
    }
    return largest;
}

std::vector<double> surface_at_samples(const FitLayout& layout, const FitAssembly& assembly,
                                       const std::vector<double>& hts)
{
    const FitSamples& smp = layout.samples;
    std::vector<double> z(smp.uv.size());
    for (int f = 0; f < layout.num_faces(); ++f)
        for (std::size_t id = smp.face_begin[f]; id < smp.face_begin[f + 1]; ++id)
            z[id] = surface_z(layout, f, assembly.weights_of(layout, f, id), hts);
    return z;
}

double worst_shortfall(const SampleHeights& samples, double clearance, const std::vector<double>& surface)
{
    double worst = 0.0;
    for (std::size_t id = 0; id < surface.size(); ++id)
        if (samples.has_data[id])
            worst = std::max(worst, samples.terrain[id] + clearance - surface[id]);
    return worst;
}

// Both surfaces reproduce constants, so every sample rises by exactly the lift.
double lift_uniformly(double shortfall, std::vector<double>& heights)
{
    if (!(shortfall > 0.0))
        return 0.0;
    const double lift = shortfall * (1.0 + 1e-12) + 1e-12;
    for (double& z : heights)
        z += lift;
    return lift;
}

void measure_fit(const SampleHeights& samples, const std::vector<double>& surface, FitReport& rep)
{
    double sum2 = 0.0;
    long long wet = 0;
    rep.min_clearance = std::numeric_limits<double>::infinity();
    for (std::size_t id = 0; id < surface.size(); ++id) {
        if (!samples.has_data[id])
            continue;
        const double z = surface[id] + rep.lift;
        const double dev = z - samples.target[id];
        rep.max_deviation = std::max(rep.max_deviation, std::abs(dev));
        sum2 += dev * dev;
        rep.min_clearance = std::min(rep.min_clearance, z - samples.terrain[id]);
        wet += samples.terrain[id] < z;
    }
    rep.rms_deviation = std::sqrt(sum2 / double(samples.with_data));
    rep.fog_fraction = double(wet) / double(samples.with_data);
}

}  // namespace kiri::geometry
