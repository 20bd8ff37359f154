#include "kiri/geometry/gregory_patch.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "kiri/geometry/error.hpp"
#include "surface/gregory_basis.hpp"

namespace kiri::geometry {
namespace {

// NaN -> centre, else clamp to [0,1]; written with selects so the batch stays vectorisable.
inline double clamp01(double t)
{
    const double c = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
    return c == c ? c : 0.5;
}

constexpr int kLanes = 8;

// One block of kLanes points: weights lane by lane, then the sums as loops over lanes.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("arch=haswell", "default")))
#endif
void evaluate_block(const double* __restrict X, const double* __restrict Y, const double* __restrict Z,
                    const double* __restrict u, const double* __restrict v, double* __restrict res)
{
    alignas(64) double w[20 * kLanes], wu[20 * kLanes], wv[20 * kLanes];
    for (int l = 0; l < kLanes; ++l)
        detail::gregory_basis<1>(clamp01(u[l]), clamp01(v[l]), kLanes, w + l, wu + l, wv + l);
    alignas(64) double acc[9 * kLanes] = {};
    for (int k = 0; k < 20; ++k) {
        const double x = X[k], y = Y[k], z = Z[k];
        for (int l = 0; l < kLanes; ++l) {
            const double a = w[k * kLanes + l], b = wu[k * kLanes + l], c = wv[k * kLanes + l];
            acc[0 * kLanes + l] += a * x;
            acc[1 * kLanes + l] += a * y;
            acc[2 * kLanes + l] += a * z;
            acc[3 * kLanes + l] += b * x;
            acc[4 * kLanes + l] += b * y;
            acc[5 * kLanes + l] += b * z;
            acc[6 * kLanes + l] += c * x;
            acc[7 * kLanes + l] += c * y;
            acc[8 * kLanes + l] += c * z;
        }
    }
    for (int i = 0; i < 9 * kLanes; ++i)
        res[i] = acc[i];
}

glm::dvec3 raw_derivatives(const GregoryPatch& patch, double u, double v, glm::dvec3& du, glm::dvec3& dv)
{
    double w[20], wu[20], wv[20];
    detail::gregory_basis<1>(u, v, 1, w, wu, wv);
    glm::dvec3 p(0.0);
    du = dv = glm::dvec3(0.0);
    const auto &X = patch.local_x(), &Y = patch.local_y(), &Z = patch.local_z();
    for (int k = 0; k < 20; ++k) {
        const glm::dvec3 q(X[k], Y[k], Z[k]);
        p += w[k] * q;
        du += wu[k] * q;
        dv += wv[k] * q;
    }
    return p;
}

// |a x b| against |a| |b|: a relative test, so it does not depend on the patch's scale.
bool normalisable(const glm::dvec3& n, const glm::dvec3& a, const glm::dvec3& b)
{
    const double len = glm::length(n);
    return std::isfinite(len) && len > 1e-14 * glm::length(a) * glm::length(b) && len > 0.0;
}

}  // namespace

GregoryPatch::GregoryPatch(const Points& points) : points_(points), origin_(points[0])
{
    for (int k = 0; k < num_points; ++k) {
        x_[k] = points[k].x - origin_.x;
        y_[k] = points[k].y - origin_.y;
        z_[k] = points[k].z - origin_.z;
    }
}

glm::dvec3 unit_normal(const GregoryPatch& patch, double u, double v, const glm::dvec3& du, const glm::dvec3& dv)
{
    glm::dvec3 n = glm::cross(du, dv);
    if (normalisable(n, du, dv))
        return glm::normalize(n);
    // The limit of the normal along the path towards the centre: a step 1e-7 inside.
    const double h = 1e-7;
    const double un = u + h * (u < 0.5 ? 1.0 : -1.0), vn = v + h * (v < 0.5 ? 1.0 : -1.0);
    glm::dvec3 a, b;
    raw_derivatives(patch, un, vn, a, b);
    n = glm::cross(a, b);
    if (normalisable(n, a, b))
        return glm::normalize(n);
    const auto& P = patch.points();
    a = P[15] - P[0];
    b = P[12] - P[3];
    n = glm::cross(a, b);
    if (normalisable(n, a, b))
        return glm::normalize(n);
    return {0.0, 0.0, 1.0};
}

PatchPoint evaluate(const GregoryPatch& patch, double u, double v)
{
    u = clamp01(u);
    v = clamp01(v);
    PatchPoint r;
    r.position = raw_derivatives(patch, u, v, r.du, r.dv) + patch.origin();
    r.normal = unit_normal(patch, u, v, r.du, r.dv);
    return r;
}

void gregory_weights(double u, double v, std::span<double, 20> w, std::span<double, 20> wu, std::span<double, 20> wv)
{
    detail::gregory_basis<1>(clamp01(u), clamp01(v), 1, w.data(), wu.data(), wv.data());
}

void PatchSamples::resize(std::size_t n, bool normals)
{
    for (auto* c : {&px, &py, &pz, &dux, &duy, &duz, &dvx, &dvy, &dvz})
        c->resize(n);
    for (auto* c : {&nx, &ny, &nz})
        c->resize(normals ? n : 0);
}

PatchSampleSpans PatchSamples::spans()
{
    return {px, py, pz, dux, duy, duz, dvx, dvy, dvz, nx, ny, nz};
}

void evaluate_into(const GregoryPatch& patch, std::span<const double> u, std::span<const double> v,
                   const PatchSampleSpans& out)
{
    const std::size_t n = u.size();
    if (v.size() != n)
        throw InputError("", "v", "u and v must have the same size");
    for (auto s : {out.px, out.py, out.pz, out.dux, out.duy, out.duz, out.dvx, out.dvy, out.dvz})
        if (s.size() < n)
            throw InputError("", "out", "an output span is shorter than the batch");
    const bool normals = !out.nx.empty() || !out.ny.empty() || !out.nz.empty();
    if (normals && (out.nx.size() < n || out.ny.size() < n || out.nz.size() < n))
        throw InputError("", "out.normal", "a normal span is shorter than the batch");
    const double *X = patch.local_x().data(), *Y = patch.local_y().data(), *Z = patch.local_z().data();
    const glm::dvec3 o = patch.origin();
    double* dst[9] = {out.px.data(),  out.py.data(),  out.pz.data(),  out.dux.data(), out.duy.data(),
                      out.duz.data(), out.dvx.data(), out.dvy.data(), out.dvz.data()};
    const double add[9] = {o.x, o.y, o.z, 0, 0, 0, 0, 0, 0};
    alignas(64) double res[9 * kLanes];
    for (std::size_t b = 0; b < n; b += kLanes) {
        const std::size_t m = std::min<std::size_t>(kLanes, n - b);
        if (m == kLanes) {
            evaluate_block(X, Y, Z, u.data() + b, v.data() + b, res);
        } else {
            double ut[kLanes], vt[kLanes];
            for (std::size_t l = 0; l < kLanes; ++l) {
                ut[l] = l < m ? u[b + l] : 0.5;
                vt[l] = l < m ? v[b + l] : 0.5;
            }
            evaluate_block(X, Y, Z, ut, vt, res);
        }
        for (int c = 0; c < 9; ++c)
            for (std::size_t l = 0; l < m; ++l)
                dst[c][b + l] = res[c * kLanes + l] + add[c];
    }
    if (!normals)
        return;
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec3 du(out.dux[i], out.duy[i], out.duz[i]), dv(out.dvx[i], out.dvy[i], out.dvz[i]);
        const glm::dvec3 c = glm::cross(du, dv);
        const glm::dvec3 nn = normalisable(c, du, dv) ? glm::normalize(c)
                                                      : unit_normal(patch, clamp01(u[i]), clamp01(v[i]), du, dv);
        out.nx[i] = nn.x;
        out.ny[i] = nn.y;
        out.nz[i] = nn.z;
    }
}

PatchSamples evaluate(const GregoryPatch& patch, std::span<const double> u, std::span<const double> v, bool normals)
{
    PatchSamples s;
    s.resize(u.size(), normals);
    evaluate_into(patch, u, v, s.spans());
    return s;
}

}  // namespace kiri::geometry
