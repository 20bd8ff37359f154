#include "reference/shell_intervals.hpp"

#include <algorithm>
#include <cmath>

#include "reference/grid_walk.hpp"

namespace kiri::geometry::detail {
namespace {

// Roots of c0 + c1 t + c2 t^2 strictly inside (ta, tb), appended to `roots`.
void quadratic_roots(double c0, double c1, double c2, double ta, double tb, double* roots, int& n)
{
    auto add = [&](double t) {
        if (t > ta && t < tb && std::isfinite(t))
            roots[n++] = t;
    };
    const double scale = std::abs(c0) + std::abs(c1) * (tb - ta) + std::abs(c2) * (tb - ta) * (tb - ta);
    if (std::abs(c2) * (tb - ta) * (tb - ta) <= 1e-14 * scale) {  // linear
        if (c1 != 0.0)
            add(-c0 / c1);
        return;
    }
    const double disc = c1 * c1 - 4.0 * c2 * c0;
    if (disc < 0.0)
        return;
    // The stable pair: no cancellation between -c1 and the root of the discriminant.
    const double q = -0.5 * (c1 + std::copysign(std::sqrt(disc), c1));
    add(q / c2);
    if (q != 0.0)
        add(c0 / q);
}

}  // namespace

void shell_intervals(const Medium& medium, const glm::dvec3& o, const glm::dvec3& d, double t0, double t1,
                     std::vector<Interval>& out)
{
    out.clear();
    const MediumGrid& g = medium.grid();
    const Bounds3& b = medium.bounds();
    if (g.nx < 2 || g.ny < 2 || !(b.max.z > b.min.z))
        return;
    // Only the slab of z where the shell can be.
    if (!clip_slab(o.z, d.z, b.min.z, b.max.z, t0, t1))
        return;
    const GridFrame frame{g.x0, g.y0, g.dx, g.dy, g.nx, g.ny};
    walk_grid(frame, o, d, t0, t1, [&](int i, int j, double ta, double tb) {
        const std::size_t k = std::size_t(j) * g.nx + i;
        const std::size_t k10 = k + 1, k01 = k + g.nx, k11 = k + g.nx + 1;
        if (g.coverage[k] <= 0.0 && g.coverage[k10] <= 0.0 && g.coverage[k01] <= 0.0 && g.coverage[k11] <= 0.0)
            return true;
        // Cell coordinates along the ray: u = u0 + u1 t, v = v0 + v1 t.
        const double u0 = (o.x - (g.x0 + i * g.dx)) / g.dx, u1 = d.x / g.dx;
        const double v0 = (o.y - (g.y0 + j * g.dy)) / g.dy, v1 = d.y / g.dy;
        // A bilinear grid f along the ray minus z: c0 + c1 t + c2 t^2.
        auto along = [&](const std::vector<double>& f, double sign, double c[3]) {
            const double a = f[k], bu = f[k10] - f[k], bv = f[k01] - f[k], e = f[k] - f[k10] - f[k01] + f[k11];
            c[0] = sign * (a + bu * u0 + bv * v0 + e * u0 * v0 - o.z);
            c[1] = sign * (bu * u1 + bv * v1 + e * (u0 * v1 + u1 * v0) - d.z);
            c[2] = sign * (e * u1 * v1);
        };
        double top[3], floor[3];
        along(g.top, 1.0, top);       // top - z >= 0 inside
        along(g.floor, -1.0, floor);  // z - floor >= 0 inside
        double cuts[6];
        int n = 0;
        cuts[n++] = ta;
        quadratic_roots(top[0], top[1], top[2], ta, tb, cuts, n);
        quadratic_roots(floor[0], floor[1], floor[2], ta, tb, cuts, n);
        for (int a = 2; a < n; ++a)  // at most four roots: insertion sort
            for (int b = a; b > 1 && cuts[b] < cuts[b - 1]; --b)
                std::swap(cuts[b], cuts[b - 1]);
        cuts[n++] = tb;
        for (int c = 0; c + 1 < n; ++c) {
            const double a = cuts[c], e = cuts[c + 1];
            if (!(e > a))
                continue;
            const double t = 0.5 * (a + e);
            const bool inside =
                top[0] + t * (top[1] + t * top[2]) >= 0.0 && floor[0] + t * (floor[1] + t * floor[2]) >= 0.0;
            if (!inside)
                continue;
            if (!out.empty() && out.back().t1 >= a - 1e-12 * (1.0 + std::abs(a)))
                out.back().t1 = e;  // continues across a cell edge
            else
                out.push_back({a, e});
        }
        return true;
    });
}

}  // namespace kiri::geometry::detail
