#pragma once
// Internal: the Bernstein and Gregory weights, written once (STYLE 6). Every Gregory path
// (single point, batch, stencils of the patch network) calls gregory_basis().
//
// REFERENCE 1.1: S(u,v) = sum_ij B_i(u) B_j(v) Q_ij(u,v) with the corrected Bernstein basis
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

namespace kiri::geometry::detail {

//! Index of P_ijk in the 20-point array (see kiri/geometry/gregory_patch.hpp).
constexpr int gregory_index(int i, int j, int k)
{
    return k == 0 ? j * 4 + i : 16 + (j - 1) * 2 + (i - 1);
}

struct Bernstein3 {
    double b[4], d[4], dd[4];
};

//! B^3_i(t) = C(3,i) t^i (1-t)^(3-i) and its first two derivatives (REFERENCE 1.1, corrected).
inline Bernstein3 bernstein3(double t)
{
    const double s = 1.0 - t;
    Bernstein3 r;
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

//! The 20 Gregory weights at (u, v) and their derivatives up to `Order` (0, 1 or 2). Weight
//! of point k goes to w[k * stride] (so a batch can store lanes side by side). Pointers of
//! orders above `Order` are not touched. Branch-free (selects only): vectorisable.
template <int Order>
inline void gregory_basis(double u, double v, std::size_t stride, double* w, double* wu = nullptr,
                          double* wv = nullptr, double* wuu = nullptr, double* wuv = nullptr,
                          double* wvv = nullptr)
{
    const Bernstein3 U = bernstein3(u), V = bernstein3(v);
    // The 12 boundary points and, for now, the full tensor weight at the 4 interior ones.
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            const std::size_t k = std::size_t(j * 4 + i) * stride;
            w[k] = U.b[i] * V.b[j];
            if constexpr (Order >= 1) {
                wu[k] = U.d[i] * V.b[j];
                wv[k] = U.b[i] * V.d[j];
            }
            if constexpr (Order >= 2) {
                wuu[k] = U.dd[i] * V.b[j];
                wuv[k] = U.d[i] * V.d[j];
                wvv[k] = U.b[i] * V.dd[j];
            }
        }
    // Interior: split T = B_i B_j into T r (P_ij0) and T q (P_ij1), plus the terms of the
    // derivatives of r (bounded forms above). sx = dx/du, sy = dy/dv.
    for (int c = 0; c < 4; ++c) {
        const int i = 1 + (c & 1), j = 1 + (c >> 1);
        const double sx = (c & 1) ? -1.0 : 1.0, sy = (c >> 1) ? -1.0 : 1.0;
        const double x = (c & 1) ? 1.0 - u : u, y = (c >> 1) ? 1.0 - v : v;
        const double cx = (c & 1) ? u : 1.0 - u, cy = (c >> 1) ? v : 1.0 - v;  // 1 - x, 1 - y
        const double s = x + y;
        const bool singular = !(s > 0.0);
        const double r = singular ? 0.5 : x / s, q = singular ? 0.5 : y / s;
        const std::size_t k0 = std::size_t(j * 4 + i) * stride, k1 = std::size_t(gregory_index(i, j, 1)) * stride;
        const double T = w[k0];
        w[k0] = T * r;
        w[k1] = T * q;
        if constexpr (Order >= 1) {
            const double cc = 9.0 * cx * cx * cy * cy;
            const double g = cc * r * q;
            const double Tu = wu[k0], Tv = wv[k0];
            const double au = sx * g * y, av = -sy * g * x;
            wu[k0] = Tu * r + au;
            wu[k1] = Tu * q - au;
            wv[k0] = Tv * r + av;
            wv[k1] = Tv * q - av;
            if constexpr (Order >= 2) {
                const double dBi = U.d[i], dBj = V.d[j];
                const double Tuu = wuu[k0], Tuv = wuv[k0], Tvv = wvv[k0];
                const double ay = 3.0 * cy * cy, ax = 3.0 * cx * cx;
                const double buu = 2.0 * sx * dBi * ay * q * q - 2.0 * cc * r * q * q;
                const double bvv = -2.0 * sy * dBj * ax * r * r + 2.0 * cc * r * r * q;
                const double buv = -sy * dBi * ay * r * q + sx * dBj * ax * r * q + sx * sy * cc * r * q * (r - q);
                wuu[k0] = Tuu * r + buu;
                wuu[k1] = Tuu * q - buu;
                wvv[k0] = Tvv * r + bvv;
                wvv[k1] = Tvv * q - bvv;
                wuv[k0] = Tuv * r + buv;
                wuv[k1] = Tuv * q - buv;
            }
        }
    }
}

}  // namespace kiri::geometry::detail
