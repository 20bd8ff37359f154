#pragma once
// Internal: the Bernstein and Gregory weights, written once. Every Gregory path
// (single point, batch, stencils of the patch network) calls gregory_basis().
//
// [Thesis] (2.1)-(2.5): S(u,v) = sum_ij B_i(u) B_j(v) Q_ij(u,v) with the corrected Bernstein basis
// B^3_i(t) = C(3,i) t^i (1-t)^(3-i). Each interior Q blends two points with weights r and
// q = 1 - r, r = x / (x + y), where (x, y) are the distances of (u, v) from the singular
// corner of that Q (Q11: (u, v), Q21: (1-u, v), Q12: (u, 1-v), Q22: (1-u, 1-v)).
//
// The derivatives of r blow up at the corner but are always multiplied by B_i(u) B_j(v) =
// 9 x (1-x)^2 y (1-y)^2; the products are rewritten in bounded form (c = 9 (1-x)^2 (1-y)^2,
// s = x + y):
//   B B r_x  = c r q y           B B r_y  = -c r q x
//   B B r_xx = -2 c r q^2        B B r_yy = 2 c r^2 q        B B r_xy = c r q (r - q)
//   B'_i(u) B_j(v) r_x = B'_i 3 (1-y)^2 q^2,  B'_i(u) B_j(v) r_y = -B'_i 3 (1-y)^2 r q
//   B_i(u) B'_j(v) r_y = -B'_j 3 (1-x)^2 r^2, B_i(u) B'_j(v) r_x = B'_j 3 (1-x)^2 r q
// so nothing is 0/0 and nothing overflows for (x, y) down to 1e-300 and below. At the
// corner itself (s = 0) r = q = 1/2: every term that holds r is multiplied by 0 there for
// the position and first derivatives, which are then their exact limits. Second
// derivatives have no limit at a singular corner (they depend on the direction of
// approach); at s = 0 they are those of the diagonal direction.
#include <cstddef>

// The batch path instantiates these for vectors of lanes; they must inline into it (a call
// would pass the vectors through memory and lose the vectorisation).
#if defined(__GNUC__)
#define KIRI_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define KIRI_ALWAYS_INLINE inline
#endif

namespace kiri::geometry::detail {

//! Index of P_ijk in the 20-point array (see kiri/geometry/surface/gregory_patch.hpp).
constexpr int gregory_index(int i, int j, int k) { return k == 0 ? j * 4 + i : 16 + (j - 1) * 2 + (i - 1); }

//! B^3_i(t) = C(3,i) t^i (1-t)^(3-i) and its first two derivatives ([Thesis] (2.1), corrected).
//! T is double or a GCC vector of doubles (the batch path's lanes).
template <class T>
struct Bernstein3 {
    T b[4], d[4], dd[4];
};

template <class T>
KIRI_ALWAYS_INLINE Bernstein3<T> bernstein3(T t)
{
    const T s = 1.0 - t;
    Bernstein3<T> r;
    r.b[0] = s * s * s;
    r.b[1] = 3.0 * t * s * s;
    r.b[2] = 3.0 * t * t * s;
    r.b[3] = t * t * t;
    r.d[0] = -3.0 * s * s;
    r.d[1] = 3.0 * s * (s - 2.0 * t);
    r.d[2] = 3.0 * t * (2.0 * s - t);
    r.d[3] = 3.0 * t * t;
    r.dd[0] = 6.0 * s;
    r.dd[1] = 6.0 * (3.0 * t - 2.0);
    r.dd[2] = 6.0 * (1.0 - 3.0 * t);
    r.dd[3] = 6.0 * t;
    return r;
}

//! The rational blend of interior corner c (0: Q11, 1: Q21, 2: Q12, 3: Q22; storage index of
//! its k = 1 point is 16 + c): Q = r P_ij0 + q P_ij1, and the bounded derivative terms
//! au = B_i B_j dr/du, av = B_i B_j dr/dv (top of this file). Shared by gregory_visit and the
//! tensor-form batch kernel, so the formula exists once.
template <class T>
struct CornerBlend {
    T r, q, au, av;
};

template <class T>
KIRI_ALWAYS_INLINE CornerBlend<T> gregory_corner(T u, T v, int c)
{
    const bool fu = (c & 1) != 0, fv = (c & 2) != 0;
    const double sx = fu ? -1.0 : 1.0, sy = fv ? -1.0 : 1.0;
    const T zero{}, half = zero + 0.5;
    const T x = fu ? 1.0 - u : u, y = fv ? 1.0 - v : v;
    const T cx = fu ? u : 1.0 - u, cy = fv ? v : 1.0 - v;  // 1 - x, 1 - y
    const T s = x + y;
    CornerBlend<T> b;
    b.r = s > zero ? x / s : half;
    b.q = s > zero ? y / s : half;
    const T g = 9.0 * cx * cx * cy * cy * b.r * b.q;
    b.au = sx * g * y;
    b.av = -sy * g * x;
    return b;
}

//! The 20 Gregory weights at (u, v) and their derivatives up to `Order` (0, 1 or 2), handed
//! to emit(k, d) point by point (k in storage order, d[0] = weight, d[1..2] = d/du, d/dv,
//! d[3..5] = d2/du2, d2/dudv, d2/dv2). Branch-free (selects only), so with T a vector of
//! lanes it evaluates several points at once.
template <int Order, class T, class Emit>
KIRI_ALWAYS_INLINE void gregory_visit(T u, T v, Emit&& emit)
{
    constexpr int N = Order == 0 ? 1 : Order == 1 ? 3 : 6;
    const Bernstein3<T> U = bernstein3(u), V = bernstein3(v);
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            T d[N];
            d[0] = U.b[i] * V.b[j];
            if constexpr (Order >= 1) {
                d[1] = U.d[i] * V.b[j];
                d[2] = U.b[i] * V.d[j];
            }
            if constexpr (Order >= 2) {
                d[3] = U.dd[i] * V.b[j];
                d[4] = U.d[i] * V.d[j];
                d[5] = U.b[i] * V.dd[j];
            }
            const bool interior = (i == 1 || i == 2) && (j == 1 || j == 2);
            if (!interior) {
                emit(j * 4 + i, d);
                continue;
            }
            // Split the tensor weight into r (P_ij0) and q (P_ij1), plus the bounded terms
            // of the derivatives of r (see the top of this file). sx = dx/du, sy = dy/dv.
            const int c = (i - 1) + 2 * (j - 1);
            const CornerBlend<T> bl = gregory_corner(u, v, c);
            const T r = bl.r, q = bl.q;
            T d0[N], d1[N];
            d0[0] = d[0] * r;
            d1[0] = d[0] * q;
            if constexpr (Order >= 1) {
                d0[1] = d[1] * r + bl.au;
                d1[1] = d[1] * q - bl.au;
                d0[2] = d[2] * r + bl.av;
                d1[2] = d[2] * q - bl.av;
                if constexpr (Order >= 2) {
                    const bool fu = i == 2, fv = j == 2;
                    const double sx = fu ? -1.0 : 1.0, sy = fv ? -1.0 : 1.0;
                    const T cx = fu ? u : 1.0 - u, cy = fv ? v : 1.0 - v;
                    const T cc = 9.0 * cx * cx * cy * cy;
                    const T dBi = U.d[i], dBj = V.d[j];
                    const T ay = 3.0 * cy * cy, ax = 3.0 * cx * cx;
                    const T buu = 2.0 * sx * dBi * ay * q * q - 2.0 * cc * r * q * q;
                    const T bvv = -2.0 * sy * dBj * ax * r * r + 2.0 * cc * r * r * q;
                    const T buv = -sy * dBi * ay * r * q + sx * dBj * ax * r * q + sx * sy * cc * r * q * (r - q);
                    d0[3] = d[3] * r + buu;
                    d1[3] = d[3] * q - buu;
                    d0[4] = d[4] * r + buv;
                    d1[4] = d[4] * q - buv;
                    d0[5] = d[5] * r + bvv;
                    d1[5] = d[5] * q - bvv;
                }
            }
            emit(j * 4 + i, d0);
            emit(gregory_index(i, j, 1), d1);
        }
}

//! Array form of gregory_visit: weight of point k goes to w[k * stride] (and wu, wv, ...).
//! Pointers of orders above `Order` are not touched.
template <int Order>
inline void gregory_basis(double u, double v, std::size_t stride, double* w, double* wu = nullptr, double* wv = nullptr,
                          double* wuu = nullptr, double* wuv = nullptr, double* wvv = nullptr)
{
    gregory_visit<Order>(u, v, [&](int k, const double* d) {
        const std::size_t o = std::size_t(k) * stride;
        w[o] = d[0];
        if constexpr (Order >= 1) {
            wu[o] = d[1];
            wv[o] = d[2];
        }
        if constexpr (Order >= 2) {
            wuu[o] = d[3];
            wuv[o] = d[4];
            wvv[o] = d[5];
        }
    });
}

}  // namespace kiri::geometry::detail
