#include "kiri/geometry/surface/gregory_patch.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "kiri/geometry/core/error.hpp"
#include "surface/gregory_basis.hpp"

// Lanes are passed only between always-inlined functions; the ABI note does not apply. Not
// popped: GCC gives the note at the end of the translation unit (a unity batch's, too).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace kiri::geometry {
namespace {

// NaN -> centre, else clamp to [0,1]; written with selects so the batch stays vectorisable.
inline double clamp_patch_parameter(double t)
{
    const double c = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
    return c == c ? c : 0.5;
}

// Lanes of the batch path: GCC/Clang vectors of doubles, 4 (one AVX2 register) where the CPU
// has AVX2 and FMA, else 2 (SSE2). gregory_visit is written for such types too, so the batch
// path evaluates the one basis several points at a time, entirely in registers.
constexpr int kMaxLanes = 4;
template <int L>
struct LanesOf {
    typedef double type __attribute__((vector_size(L * sizeof(double))));
};

template <class V>
KIRI_ALWAYS_INLINE V clamp_lanes(V t)
{
    const V zero{}, one = zero + 1.0, half = zero + 0.5;
    const V c = t < zero ? zero : (t > one ? one : t);
    return c == c ? c : half;
}

// Tensor form of the same patch (fewer operations than summing 20 weighted points): blend
// the four interior Q_ij (gregory_corner, the shared formula), run the bicubic Bezier sums
// over the 4 x 4 net of Q, then add the terms of the derivatives of the blends.
template <int L>
KIRI_ALWAYS_INLINE void blocks_impl(const double* __restrict X, const double* __restrict Y, const double* __restrict Z,
                                    const double* __restrict u, const double* __restrict v, std::size_t n,
                                    double* const* __restrict dst, const double* add)
{
    using V = typename LanesOf<L>::type;
    const double* P[3] = {X, Y, Z};
    for (std::size_t b = 0; b + L <= n; b += L) {
        V U, W;
        __builtin_memcpy(&U, u + b, sizeof U);
        __builtin_memcpy(&W, v + b, sizeof W);
        U = clamp_lanes(U);
        W = clamp_lanes(W);
        const detail::Bernstein3<V> Bu = detail::bernstein3(U), Bv = detail::bernstein3(W);
        detail::CornerBlend<V> bl[4];
        for (int c = 0; c < 4; ++c)
            bl[c] = detail::gregory_corner(U, W, c);
        for (int a = 0; a < 3; ++a) {
            const double* p = P[a];
            V pos{}, du{}, dv{};
            for (int j = 0; j < 4; ++j) {
                V row{}, row_u{};
                for (int i = 0; i < 4; ++i) {
                    const bool interior = (i == 1 || i == 2) && (j == 1 || j == 2);
                    V q;
                    if (interior) {
                        const int c = (i - 1) + 2 * (j - 1);
                        const double p0 = p[j * 4 + i], p1 = p[16 + c];
                        q = p1 + bl[c].r * (p0 - p1);
                    } else {
                        q = V{} + p[j * 4 + i];
                    }
                    row += Bu.b[i] * q;
                    row_u += Bu.d[i] * q;
                }
                pos += Bv.b[j] * row;
                du += Bv.b[j] * row_u;
                dv += Bv.d[j] * row;
            }
            for (int c = 0; c < 4; ++c) {
                const int i = 1 + (c & 1), j = 1 + (c >> 1);
                const double diff = p[j * 4 + i] - p[16 + c];
                du += bl[c].au * diff;
                dv += bl[c].av * diff;
            }
            const V out[3] = {pos + add[a], du, dv};
            for (int o = 0; o < 3; ++o)
                __builtin_memcpy(dst[3 * o + a] + b, &out[o], sizeof(V));
        }
    }
}

using BlocksFn = void (*)(const double*, const double*, const double*, const double*, const double*, std::size_t,
                          double* const*, const double*);

// n must be a multiple of kMaxLanes.
void blocks_sse2(const double* X, const double* Y, const double* Z, const double* u, const double* v, std::size_t n,
                 double* const* dst, const double* add)
{
    blocks_impl<2>(X, Y, Z, u, v, n, dst, add);
}

// KIRI_GREGORY_NO_AVX2: build without the AVX2 path (to measure the SSE2 one).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(KIRI_GREGORY_NO_AVX2)
__attribute__((target("avx2,fma"))) void blocks_avx2(const double* X, const double* Y, const double* Z, const double* u,
                                                     const double* v, std::size_t n, double* const* dst,
                                                     const double* add)
{
    blocks_impl<4>(X, Y, Z, u, v, n, dst, add);
}
#endif

BlocksFn pick_blocks()
{
#if defined(__x86_64__) && defined(__GNUC__) && !defined(KIRI_GREGORY_NO_AVX2)
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
        return blocks_avx2;
#endif
    return blocks_sse2;
}

const BlocksFn evaluate_blocks = pick_blocks();

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
    u = clamp_patch_parameter(u);
    v = clamp_patch_parameter(v);
    PatchPoint r;
    r.position = raw_derivatives(patch, u, v, r.du, r.dv) + patch.origin();
    r.normal = unit_normal(patch, u, v, r.du, r.dv);
    return r;
}

void gregory_weights(double u, double v, std::span<double, 20> w, std::span<double, 20> wu, std::span<double, 20> wv)
{
    detail::gregory_basis<1>(clamp_patch_parameter(u), clamp_patch_parameter(v), 1, w.data(), wu.data(), wv.data());
}

void PatchSamples::resize(std::size_t n, bool normals)
{
    for (auto* c : {&px, &py, &pz, &dux, &duy, &duz, &dvx, &dvy, &dvz})
        c->resize(n);
    for (auto* c : {&nx, &ny, &nz})
        c->resize(normals ? n : 0);
}

PatchSampleSpans PatchSamples::spans() { return {px, py, pz, dux, duy, duz, dvx, dvy, dvz, nx, ny, nz}; }

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
    const std::size_t full = n / kMaxLanes * kMaxLanes;
    evaluate_blocks(X, Y, Z, u.data(), v.data(), full, dst, add);
    if (const std::size_t m = n - full; m > 0) {
        // The tail: padded to one block, written back lane by lane.
        double ut[kMaxLanes], vt[kMaxLanes], res[9][kMaxLanes];
        double* rd[9];
        for (int c = 0; c < 9; ++c)
            rd[c] = res[c];
        for (std::size_t l = 0; l < std::size_t(kMaxLanes); ++l) {
            ut[l] = l < m ? u[full + l] : 0.5;
            vt[l] = l < m ? v[full + l] : 0.5;
        }
        evaluate_blocks(X, Y, Z, ut, vt, kMaxLanes, rd, add);
        for (int c = 0; c < 9; ++c)
            for (std::size_t l = 0; l < m; ++l)
                dst[c][full + l] = res[c][l];
    }
    if (!normals)
        return;
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec3 du(out.dux[i], out.duy[i], out.duz[i]), dv(out.dvx[i], out.dvy[i], out.dvz[i]);
        const glm::dvec3 c = glm::cross(du, dv);
        const glm::dvec3 nn = normalisable(c, du, dv)
            ? glm::normalize(c)
            : unit_normal(patch, clamp_patch_parameter(u[i]), clamp_patch_parameter(v[i]), du, dv);
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
