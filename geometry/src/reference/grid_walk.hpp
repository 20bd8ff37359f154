#pragma once
// Internal: the cells of a regular 2D grid that a ray crosses, in order ([Amanatides87]). Cell
// (i, j) spans [x0 + i dx, x0 + (i + 1) dx] x [y0 + j dy, y0 + (j + 1) dy], 0 <= i <= nx - 2,
// 0 <= j <= ny - 2: the cells between the samples of a Heightfield or a MediumGrid.
#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/vec3.hpp>

namespace kiri::geometry::detail {

//! +infinity: the far end of a ray segment that nothing bounds.
inline constexpr double inf = std::numeric_limits<double>::infinity();

struct GridFrame {
    double x0 = 0.0, y0 = 0.0, dx = 1.0, dy = 1.0;
    int nx = 0, ny = 0;  // samples
    double x1() const { return x0 + (nx - 1) * dx; }
    double y1() const { return y0 + (ny - 1) * dy; }
};

//! Clips [t0, t1] to the slab lo <= o + t d <= hi of one axis; false when nothing is left.
inline bool clip_slab(double o, double d, double lo, double hi, double& t0, double& t1)
{
    if (d == 0.0)
        return o >= lo && o <= hi;
    double a = (lo - o) / d, b = (hi - o) / d;
    if (a > b)
        std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    return t0 <= t1;
}

//! Calls visit(i, j, ta, tb) for every cell the ray o + t d crosses for t in [t0, t1] (only
//! its x and y matter), nearest first, until visit returns false. t1 may be +inf.
template <class Visit>
void walk_grid(const GridFrame& g, const glm::dvec3& o, const glm::dvec3& d, double t0, double t1, Visit&& visit)
{
    if (g.nx < 2 || g.ny < 2 || !(t1 >= t0))
        return;
    if (!clip_slab(o.x, d.x, g.x0, g.x1(), t0, t1) || !clip_slab(o.y, d.y, g.y0, g.y1(), t0, t1))
        return;
    const double tm = 0.5 * (t0 + t1);
    // The cell of the segment's start, nudged inside along the ray for starts on a boundary.
    const double px = o.x + d.x * (std::isinf(tm) ? t0 : std::min(t0 + 1e-9 * (tm - t0), tm));
    const double py = o.y + d.y * (std::isinf(tm) ? t0 : std::min(t0 + 1e-9 * (tm - t0), tm));
    int i = std::clamp(int(std::floor((px - g.x0) / g.dx)), 0, g.nx - 2);
    int j = std::clamp(int(std::floor((py - g.y0) / g.dy)), 0, g.ny - 2);
    const int si = d.x > 0.0 ? 1 : -1, sj = d.y > 0.0 ? 1 : -1;
    double next_x = d.x != 0.0 ? (g.x0 + (i + (d.x > 0.0 ? 1 : 0)) * g.dx - o.x) / d.x : inf;
    double next_y = d.y != 0.0 ? (g.y0 + (j + (d.y > 0.0 ? 1 : 0)) * g.dy - o.y) / d.y : inf;
    const double step_x = d.x != 0.0 ? g.dx / std::abs(d.x) : inf;
    const double step_y = d.y != 0.0 ? g.dy / std::abs(d.y) : inf;
    double t = t0;
    for (;;) {
        const double t_next = std::min({next_x, next_y, t1});
        if (t_next > t && !visit(i, j, t, t_next))
            return;
        if (t_next >= t1)
            return;
        t = std::max(t, t_next);
        if (next_x <= next_y) {
            i += si;
            next_x += step_x;
        } else {
            j += sj;
            next_y += step_y;
        }
        if (i < 0 || j < 0 || i > g.nx - 2 || j > g.ny - 2)
            return;
    }
}

}  // namespace kiri::geometry::detail
