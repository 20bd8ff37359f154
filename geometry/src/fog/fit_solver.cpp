#include "fog/fit_solver.hpp"

#include <algorithm>

#include "kiri/geometry/core/error.hpp"

namespace kiri::geometry {
namespace {

// A faint pull of each control height towards the target under it keeps the system positive
// definite where a vertex has no data (nodata, smoothness 0); it is exact for planes (affine
// precision of both surfaces).
constexpr double pull_weight = 1e-9;

}  // namespace

FitSolver::FitSolver(const FitLayout& layout, std::vector<double> vertex_target)
    : layout_(layout), vertex_target_(std::move(vertex_target)), normal_(layout.num_vertices(), layout.num_vertices())
{
    const int nf = layout.num_faces(), nv = layout.num_vertices();
    const FaceStencils& stencils = layout.stencils;
    std::vector<Eigen::Triplet<double>> trip;
    for (int v = 0; v < nv; ++v)
        trip.emplace_back(v, v, 0.0);
    for (int f = 0; f < nf; ++f)
        for (int r : stencils.support(f))
            for (int c : stencils.support(f))
                trip.emplace_back(r, c, 0.0);
    normal_.setFromTriplets(trip.begin(), trip.end());
    auto find = [&](int r, int c) {
        const int* begin = normal_.innerIndexPtr() + normal_.outerIndexPtr()[c];
        const int* end = normal_.innerIndexPtr() + normal_.outerIndexPtr()[c + 1];
        return int(std::lower_bound(begin, end, r) - normal_.innerIndexPtr());
    };
    diagonal_slot_.resize(nv);
    for (int v = 0; v < nv; ++v)
        diagonal_slot_[v] = find(v, v);
    face_slot_.resize(nf);
    for (int f = 0; f < nf; ++f) {
        const auto& S = stencils.support(f);
        face_slot_[f].resize(S.size() * S.size());
        for (std::size_t r = 0; r < S.size(); ++r)
            for (std::size_t c = 0; c < S.size(); ++c)
                face_slot_[f][r * S.size() + c] = find(S[r], S[c]);
    }
    cholesky_.analyzePattern(normal_);
}

std::vector<double> FitSolver::solve(const std::vector<FaceSystem>& faces)
{
    const int nf = layout_.num_faces(), nv = layout_.num_vertices();
    double* val = normal_.valuePtr();
    std::fill(val, val + normal_.nonZeros(), 0.0);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(nv);
    for (int v = 0; v < nv; ++v) {
        val[diagonal_slot_[v]] += pull_weight;
        rhs[v] += pull_weight * vertex_target_[v];
    }
    for (int f = 0; f < nf; ++f) {
        const auto& S = layout_.stencils.support(f);
        const std::size_t n = S.size();
        for (std::size_t a = 0; a < n; ++a)
            rhs[S[a]] += faces[f].r[a];
        for (std::size_t k = 0; k < n * n; ++k)
            val[face_slot_[f][k]] += faces[f].L[k];
    }
    cholesky_.factorize(normal_);
    if (cholesky_.info() != Eigen::Success)
        throw InputError("", "fit", "the least-squares system is singular");
    const Eigen::VectorXd x = cholesky_.solve(rhs);
    std::vector<double> heights(nv);
    for (int v = 0; v < nv; ++v)
        heights[v] = x[v];
    ++solves_;
    return heights;
}

}  // namespace kiri::geometry
