#include "kiri/geometry/fog/base_surface.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/fog/fog_target.hpp"
#include "fog/fit_samples.hpp"
#include "surface/face_stencil.hpp"

namespace kiri::geometry {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string num(double v)
{
    std::ostringstream s;
    s << v;
    return s.str();
}

void require_finite(double v, const char* field)
{
    if (!std::isfinite(v))
        throw InputError("", field, "must be a finite number");
}

// Per-face normal equations of the fit: L h_S = r over the face's support S.
struct FaceSystem {
    std::vector<double> L, r;
};

void add_row(FaceSystem& s, const std::vector<double>& w, double weight, double rhs)
{
    const std::size_t n = w.size();
    for (std::size_t a = 0; a < n; ++a) {
        const double wa = weight * w[a];
        s.r[a] += wa * rhs;
        for (std::size_t b = 0; b < n; ++b)
            s.L[a * n + b] += wa * w[b];
    }
}

}  // namespace

const char* to_string(FitMode mode) { return mode == FitMode::blanket ? "blanket" : "lake"; }

BaseSurface::BaseSurface(ControlMesh control, SurfaceKind kind) : control_(std::move(control)), kind_(kind)
{
    stencils_ = kind == SurfaceKind::gregory ? make_gregory_stencils(control_.mesh)
                                             : make_catmull_clark_stencils(control_.mesh);
    surface_ = make_surface(control_.mesh, kind);
}
BaseSurface::~BaseSurface() = default;
BaseSurface::BaseSurface(BaseSurface&&) noexcept = default;
BaseSurface& BaseSurface::operator=(BaseSurface&&) noexcept = default;

std::vector<double> BaseSurface::heights() const
{
    std::vector<double> z;
    z.reserve(control_.mesh.n_vertices());
    for (auto v : control_.mesh.vertices())
        z.push_back(control_.mesh.point(v)[2]);
    return z;
}

void BaseSurface::set_heights(const std::vector<double>& z)
{
    if (z.size() != control_.mesh.n_vertices())
        throw InputError("", "heights", "expected one height per control vertex");
    for (auto v : control_.mesh.vertices()) {
        auto p = control_.mesh.point(v);
        p[2] = z[v.idx()];
        control_.mesh.set_point(v, p);
    }
    std::vector<glm::dvec3> points(z.size());
    for (auto v : control_.mesh.vertices()) {
        const auto p = control_.mesh.point(v);
        points[v.idx()] = {p[0], p[1], p[2]};
    }
    surface_->set_control_points(points);
}

glm::dvec3 BaseSurface::evaluate(int face, double u, double v, glm::dvec3* du, glm::dvec3* dv) const
{
    const PatchPoint q = surface_->evaluate(face, u, v);
    if (du)
        *du = q.du;
    if (dv)
        *dv = q.dv;
    return q.position;
}

FitReport BaseSurface::fit(const Terrain& terrain, const FitOptions& o)
{
    for (auto [v, name] : {std::pair{o.offset, "offset"},
                           {o.smoothing_length, "smoothing"},
                           {o.altitude, "altitude"},
                           {o.clearance, "clearance"},
                           {o.thickness, "thickness"},
                           {o.smoothness, "smoothness"}})
        require_finite(v, name);
    if (o.smoothness < 0.0)
        throw InputError("", "smoothness", "must be >= 0");
    if (o.mode == FitMode::blanket) {
        if (o.clearance < 0.0)
            throw InputError("", "clearance", "must be >= 0");
        if (!(o.thickness > 0.0))
            throw InputError("", "thickness", "must be > 0");
        if (o.clearance > o.thickness)
            throw InputError("", "clearance",
                             "clearance " + num(o.clearance) + " m is larger than the fog thickness " +
                                 num(o.thickness) + " m: the fog would never touch the ground");
    }
    FitReport rep;
    const Heightfield& hf = terrain.heightfield();
    auto t0 = std::chrono::steady_clock::now();
    const Heightfield smooth = o.mode == FitMode::blanket ? smooth_heightfield(hf, o.smoothing_length) : Heightfield{};
    auto target_at = [&](double x, double y) {
        if (o.mode == FitMode::blanket)
            return sample_bilinear(smooth, x, y) + o.offset;
        return o.altitude_grid ? sample_bilinear(*o.altitude_grid, x, y) : o.altitude;
    };
    rep.seconds_target = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();

    const double h = control_.patch_size;
    const int K = o.samples_per_patch > 0 ? o.samples_per_patch : 4;
    rep.samples_per_patch = K;
    const int nf = num_patches(), nv = control_.num_vertices();
    const std::vector<double> key = {double(hf.nx), double(hf.ny), hf.dx, hf.dy, hf.x0, hf.y0, double(K)};
    rep.samples_reused = samples_ && samples_key_ == key;
    if (!rep.samples_reused) {
        samples_ = std::make_shared<const FitSamples>(make_fit_samples(control_, *stencils_, hf, K, true));
        samples_key_ = key;
    }
    const FitSamples& smp = *samples_;
    rep.grid_vertex_samples = smp.grid_vertex_samples;
    const std::size_t ns = smp.uv.size();
    const glm::dvec2 origin = control_.origin;
    std::vector<glm::dvec2> rel(nv);
    for (int v = 0; v < nv; ++v) {
        const auto p = control_.mesh.point(PolyMesh::VertexHandle(v));
        rel[v] = glm::dvec2(p[0], p[1]) - origin;
    }
    std::vector<double> hts = heights();

    // Data term and thin-plate energy, face by face (FitOptions::smoothness). Each face's
    // samples share a data weight of 1 (alpha per sample).
    std::vector<double> alpha(nf);
    for (int f = 0; f < nf; ++f)
        alpha[f] = 1.0 / double(std::max<std::size_t>(1, smp.face_begin[f + 1] - smp.face_begin[f]));
    const double gq[3] = {0.5 - 0.5 * std::sqrt(0.6), 0.5, 0.5 + 0.5 * std::sqrt(0.6)};
    const double gw[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
    std::vector<FaceSystem> sys(nf);
    FaceWeights fw;
    std::vector<double> hxx, hxy, hyy;
    long long valid_samples = 0;
    // Terrain height and target cached per sample; xy come from the fixed control xy.
    std::vector<double> sample_terrain(ns), sample_target(ns);
    std::vector<std::uint8_t> sample_state(ns, 0);  // bit 0: has data, bit 1: held
    for (int f = 0; f < nf; ++f) {
        const auto& S = stencils_->support(f);
        const std::size_t n = S.size();
        sys[f].L.assign(n * n, 0.0);
        sys[f].r.assign(n, 0.0);
        for (std::size_t id = smp.face_begin[f]; id < smp.face_begin[f + 1]; ++id) {
            stencils_->weights(f, smp.uv[id].x, smp.uv[id].y, fw, 0);
            glm::dvec2 xy(0.0);
            for (std::size_t k = 0; k < n; ++k)
                xy += fw.w[k] * rel[S[k]];
            xy += origin;
            sample_terrain[id] = terrain.height(xy.x, xy.y);
            sample_target[id] = target_at(xy.x, xy.y);
            if (!has_data(hf, xy.x, xy.y)) {
                ++rep.nodata_samples;
                continue;
            }
            sample_state[id] = 1;
            ++valid_samples;
            // Blanket: fit the upper envelope of the target and terrain + clearance, so the
            // constraint iterations below start close to feasible.
            const double fit_to = o.mode == FitMode::blanket
                ? std::max(sample_target[id], sample_terrain[id] + o.clearance)
                : sample_target[id];
            add_row(sys[f], fw.w, alpha[f], fit_to);
        }
        if (o.smoothness <= 0.0)
            continue;
        for (int qb = 0; qb < 3; ++qb)
            for (int qa = 0; qa < 3; ++qa) {
                stencils_->weights(f, gq[qa], gq[qb], fw, 2);
                glm::dvec2 au(0.0), av(0.0), auu(0.0), auv(0.0), avv(0.0);
                for (std::size_t k = 0; k < n; ++k) {
                    au += fw.wu[k] * rel[S[k]];
                    av += fw.wv[k] * rel[S[k]];
                    auu += fw.wuu[k] * rel[S[k]];
                    auv += fw.wuv[k] * rel[S[k]];
                    avv += fw.wvv[k] * rel[S[k]];
                }
                const double det = au.x * av.y - av.x * au.y;
                if (!(std::abs(det) > 1e-12 * h * h))
                    continue;
                // z_x, z_y from z_u, z_v; then the xy Hessian H = J^-T A J^-1 with
                // A = [z_uu - grad z . x_uu, ...] (chain rule; x(u, v) is fixed, so H is linear in z).
                const double M[2][2] = {{av.y / det, -av.x / det}, {-au.y / det, au.x / det}};
                hxx.assign(n, 0.0);
                hxy.assign(n, 0.0);
                hyy.assign(n, 0.0);
                for (std::size_t k = 0; k < n; ++k) {
                    const double gx = (av.y * fw.wu[k] - au.y * fw.wv[k]) / det;
                    const double gy = (-av.x * fw.wu[k] + au.x * fw.wv[k]) / det;
                    const double A[2][2] = {{fw.wuu[k] - gx * auu.x - gy * auu.y, fw.wuv[k] - gx * auv.x - gy * auv.y},
                                            {fw.wuv[k] - gx * auv.x - gy * auv.y, fw.wvv[k] - gx * avv.x - gy * avv.y}};
                    auto H = [&](int i, int j) {
                        double s = 0.0;
                        for (int c = 0; c < 2; ++c)
                            for (int d = 0; d < 2; ++d)
                                s += M[c][i] * A[c][d] * M[d][j];
                        return s;
                    };
                    hxx[k] = H(0, 0);
                    hxy[k] = H(0, 1);
                    hyy[k] = H(1, 1);
                }
                const double beta = o.smoothness * h * h * h * h * gw[qa] * gw[qb] * std::abs(det) / (h * h);
                add_row(sys[f], hxx, beta, 0.0);
                add_row(sys[f], hxy, 2.0 * beta, 0.0);
                add_row(sys[f], hyy, beta, 0.0);
            }
    }
    rep.samples = valid_samples + rep.nodata_samples;
    if (valid_samples == 0)
        throw InputError("", "footprint", "no terrain data under the footprint (all samples are nodata)");
    if (o.mode == FitMode::lake) {
        long long below = 0;
        for (std::size_t id = 0; id < sample_state.size(); ++id)
            below += (sample_state[id] & 1) && sample_terrain[id] < sample_target[id];
        if (below == 0)
            throw InputError(
                "", "altitude",
                (o.altitude_grid ? std::string("the fog top") : "the lake altitude " + num(o.altitude) + " m") +
                    " is below the terrain everywhere in the footprint: no fog");
    }

    // A faint pull of each control height towards the target under it keeps the system
    // positive definite where a vertex has no data (nodata, smoothness 0); it is exact for
    // planes (affine precision of both surfaces).
    std::vector<double> reg_target(nv);
    for (int v = 0; v < nv; ++v)
        reg_target[v] = target_at(rel[v].x + origin.x, rel[v].y + origin.y);
    const double eps = 1e-9;
    rep.seconds_assemble = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();

    // The normal matrix's sparsity is fixed by the topology: build it and the slot of every
    // face-local entry once; each solve only scatters values and refactorises.
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
    Eigen::SparseMatrix<double> N(nv, nv);
    std::vector<std::vector<int>> slot(nf);
    std::vector<int> diag_slot(nv);
    {
        std::vector<Eigen::Triplet<double>> trip;
        for (int v = 0; v < nv; ++v)
            trip.emplace_back(v, v, 0.0);
        for (int f = 0; f < nf; ++f)
            for (int r : stencils_->support(f))
                for (int c : stencils_->support(f))
                    trip.emplace_back(r, c, 0.0);
        N.setFromTriplets(trip.begin(), trip.end());
        auto find = [&](int r, int c) {
            const int* begin = N.innerIndexPtr() + N.outerIndexPtr()[c];
            const int* end = N.innerIndexPtr() + N.outerIndexPtr()[c + 1];
            return int(std::lower_bound(begin, end, r) - N.innerIndexPtr());
        };
        for (int v = 0; v < nv; ++v)
            diag_slot[v] = find(v, v);
        for (int f = 0; f < nf; ++f) {
            const auto& S = stencils_->support(f);
            slot[f].resize(S.size() * S.size());
            for (std::size_t r = 0; r < S.size(); ++r)
                for (std::size_t c = 0; c < S.size(); ++c)
                    slot[f][r * S.size() + c] = find(S[r], S[c]);
        }
        solver.analyzePattern(N);
    }
    auto solve = [&]() {
        double* val = N.valuePtr();
        std::fill(val, val + N.nonZeros(), 0.0);
        Eigen::VectorXd rhs = Eigen::VectorXd::Zero(nv);
        for (int v = 0; v < nv; ++v) {
            val[diag_slot[v]] += eps;
            rhs[v] += eps * reg_target[v];
        }
        for (int f = 0; f < nf; ++f) {
            const auto& S = stencils_->support(f);
            const std::size_t n = S.size();
            for (std::size_t a = 0; a < n; ++a)
                rhs[S[a]] += sys[f].r[a];
            for (std::size_t k = 0; k < n * n; ++k)
                val[slot[f][k]] += sys[f].L[k];
        }
        solver.factorize(N);
        if (solver.info() != Eigen::Success)
            throw InputError("", "fit", "the least-squares system is singular");
        const Eigen::VectorXd x = solver.solve(rhs);
        for (int v = 0; v < nv; ++v)
            hts[v] = x[v];
        ++rep.iterations;
    };
    auto surface_z = [&](int f, const std::vector<double>& w) {
        const auto& S = stencils_->support(f);
        double z = 0.0;
        for (std::size_t k = 0; k < S.size(); ++k)
            z += w[k] * hts[S[k]];
        return z;
    };

    solve();
    // Blanket: z >= terrain + clearance at every sample, by augmented-Lagrangian (Uzawa)
    // iterations on the violated samples. Each sample carries t >= 0 (its multiplier over the
    // penalty, in metres); a sample is held, with a penalty rho (300 x a sample's data weight;
    // stiffer penalties oscillate on Jacksboro) towards terrain + clearance + t, while
    // t + (need - z) > 0, and after each solve t grows by what the sample still lacks.
    // Raising the held targets rather than holding them at equality is what resolves
    // conflicts between held samples (a peak narrower than a patch): the converged t are the
    // constraint forces of the exact inequality-constrained least-squares problem. What is
    // left after max_active_set_iterations goes to the guarantee steps below.
    const double rho = 300.0, tol = 1e-3;
    if (o.mode == FitMode::blanket) {
        const std::vector<FaceSystem> base = sys;
        std::vector<float> raise(ns, 0.0f);
        // Samples far above their bound are skipped until the heights have moved enough to
        // reach them: a face's samples move by at most kStencilBound x the largest height
        // change of its support (the weights' absolute sum; 1 for B-spline patches).
        constexpr double kStencilBound = 2.0;
        const double inf = std::numeric_limits<double>::infinity();
        std::vector<double> moved(nf, inf), min_slack(nf, -inf);
        // The one-step inner solves can cycle on hard terrains: keep the best iterate.
        std::vector<double> best = hts;
        double best_worst = inf;
        for (int it = 0; it < o.max_active_set_iterations; ++it) {
            long long held = 0;
            double worst = 0.0;
            for (int f = 0; f < nf; ++f) {
                sys[f] = base[f];
                const bool full = !(moved[f] < min_slack[f]);
                if (full) {
                    moved[f] = 0.0;
                    min_slack[f] = inf;
                }
                for (std::size_t id = smp.face_begin[f]; id < smp.face_begin[f + 1]; ++id) {
                    if (!(sample_state[id] & 1))
                        continue;
                    const bool was = sample_state[id] & 2;
                    if (!was && !full)
                        continue;
                    stencils_->weights(f, smp.uv[id].x, smp.uv[id].y, fw, 0);
                    const double need = sample_terrain[id] + o.clearance, lack = need - surface_z(f, fw.w);
                    worst = std::max(worst, lack);
                    if (was)
                        raise[id] = float(std::max(0.0, double(raise[id]) + lack));
                    const bool hold = double(raise[id]) + lack > 0.0;
                    sample_state[id] = std::uint8_t(1 | (hold ? 2 : 0));
                    if (hold) {
                        add_row(sys[f], fw.w, rho * alpha[f], need + double(raise[id]));
                        ++held;
                    } else if (full) {
                        min_slack[f] = std::min(min_slack[f], -lack - double(raise[id]));
                    }
                }
            }
            rep.active_constraints = held;
            if (worst < best_worst) {
                best_worst = worst;
                best = hts;
            }
            if (worst <= tol)
                break;
            const std::vector<double> before = hts;
            solve();
            for (int f = 0; f < nf; ++f) {
                double d = 0.0;
                for (int v : stencils_->support(f))
                    d = std::max(d, std::abs(hts[v] - before[v]));
                moved[f] += kStencilBound * d;
            }
        }
        hts = best;  // (the last solve is unchecked: the loop ends on a check when it converges)
    }

    // Local guarantee (blanket): raise the control vertices under each sample still short of
    // terrain + clearance by its shortfall (the positive weights of a sample sum to >= 1, so
    // the sample rises at least that much); a few passes settle the interplay of neighbours.
    if (o.mode == FitMode::blanket)
        for (int pass = 0; pass < 4; ++pass) {
            std::vector<double> up(nv, 0.0);
            double worst = 0.0;
            for (int f = 0; f < nf; ++f) {
                const auto& S = stencils_->support(f);
                for (std::size_t id = smp.face_begin[f]; id < smp.face_begin[f + 1]; ++id) {
                    if (!(sample_state[id] & 1))
                        continue;
                    stencils_->weights(f, smp.uv[id].x, smp.uv[id].y, fw, 0);
                    const double lack = sample_terrain[id] + o.clearance - surface_z(f, fw.w);
                    if (lack <= 0.0)
                        continue;
                    worst = std::max(worst, lack);
                    for (std::size_t k = 0; k < S.size(); ++k)
                        if (fw.w[k] > 1e-12)
                            up[S[k]] = std::max(up[S[k]], lack * (1.0 + 1e-9));
                }
            }
            if (worst == 0.0)
                break;
            for (int v = 0; v < nv; ++v) {
                hts[v] += up[v];
                rep.local_lift = std::max(rep.local_lift, up[v]);
            }
        }

    // Final guarantee (blanket): lift the whole surface by the worst remaining violation;
    // both surfaces reproduce constants, so every sample rises by exactly that much.
    std::vector<double> z_all(ns);
    double worst = 0.0;
    for (int f = 0; f < nf; ++f)
        for (std::size_t id = smp.face_begin[f]; id < smp.face_begin[f + 1]; ++id) {
            stencils_->weights(f, smp.uv[id].x, smp.uv[id].y, fw, 0);
            z_all[id] = surface_z(f, fw.w);
            if (sample_state[id] & 1)
                worst = std::max(worst, sample_terrain[id] + o.clearance - z_all[id]);
        }
    if (o.mode == FitMode::blanket && worst > 0.0) {
        rep.lift = worst * (1.0 + 1e-12) + 1e-12;
        for (double& z : hts)
            z += rep.lift;
    }
    double sum2 = 0.0;
    long long wet = 0;
    rep.min_clearance = std::numeric_limits<double>::infinity();
    for (std::size_t id = 0; id < z_all.size(); ++id) {
        if (!(sample_state[id] & 1))
            continue;
        const double z = z_all[id] + rep.lift;
        const double dev = z - sample_target[id];
        rep.max_deviation = std::max(rep.max_deviation, std::abs(dev));
        sum2 += dev * dev;
        rep.min_clearance = std::min(rep.min_clearance, z - sample_terrain[id]);
        wet += sample_terrain[id] < z;
    }
    rep.rms_deviation = std::sqrt(sum2 / double(valid_samples));
    rep.fog_fraction = double(wet) / double(valid_samples);
    for (double z : hts)
        if (!std::isfinite(z))
            throw InputError("", "fit", "the fit produced a non-finite height");
    set_heights(hts);
    rep.seconds_solve = seconds_since(t0);
    return rep;
}

}  // namespace kiri::geometry
