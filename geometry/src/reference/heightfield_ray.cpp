#include "reference/heightfield_ray.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

namespace kiri::geometry::detail {

HeightfieldRay::HeightfieldRay(const Heightfield& hf) : hf_(hf), frame_{hf.x0, hf.y0, hf.dx, hf.dy, hf.nx, hf.ny}
{
    if (!hf.z.empty()) {
        const auto [lo, hi] = std::minmax_element(hf.z.begin(), hf.z.end());
        z_min_ = *lo;
        z_max_ = *hi;
    }
}

double HeightfieldRay::cell_height(int i, int j, double s, double r) const
{
    s = std::clamp(s, 0.0, 1.0);
    r = std::clamp(r, 0.0, 1.0);
    const double z00 = hf_.at(i, j), z11 = hf_.at(i + 1, j + 1);
    if (s >= r)
        return z00 + s * (hf_.at(i + 1, j) - z00) + r * (z11 - hf_.at(i + 1, j));
    return z00 + r * (hf_.at(i, j + 1) - z00) + s * (z11 - hf_.at(i, j + 1));
}

std::optional<double> HeightfieldRay::first_hit(const glm::dvec3& o, const glm::dvec3& d, double t0, double t1) const
{
    if (hf_.nx < 2 || hf_.ny < 2)
        return std::nullopt;
    // A hit needs z_min <= z <= z_max: clip the segment to that slab first (rays towards the
    // sun leave it quickly, so shadow queries stay short).
    const double t_start = t0;
    if (!clip_slab(o.z, d.z, -std::numeric_limits<double>::infinity(), z_max_, t0, t1))
        return std::nullopt;
    std::optional<double> hit;
    // A ray from outside the grid that enters it under the terrain's edge passes beneath the
    // surface, as the GL terrain (a surface, not a solid) and the shadow map draw it: the grid's
    // edge is no wall. It hits only once it has come out above the surface.
    const bool outside = o.x < hf_.x0 || o.x > hf_.x_max() || o.y < hf_.y0 || o.y > hf_.y_max();
    // Where the ray enters the grid's footprint: before the slab (from above) it cannot be under.
    double t_enter = t_start;
    for (const auto [p, v, lo, hi] :
         {std::array<double, 4>{o.x, d.x, hf_.x0, hf_.x_max()}, std::array<double, 4>{o.y, d.y, hf_.y0, hf_.y_max()}})
        if (v != 0.0)
            t_enter = std::max(t_enter, std::min((lo - p) / v, (hi - p) / v));
    bool under = outside && t_enter >= t0;
    walk_grid(frame_, o, d, t0, t1, [&](int i, int j, double ta, double tb) {
        const double xi = hf_.x_of(i), yj = hf_.y_of(j);
        // Ray height above the terrain, piecewise linear in t with a kink where the ray
        // crosses the cell's diagonal s = r.
        auto gap = [&](double t) {
            const double s = (o.x + d.x * t - xi) / hf_.dx, r = (o.y + d.y * t - yj) / hf_.dy;
            return o.z + d.z * t - cell_height(i, j, s, r);
        };
        double ts[3] = {ta, tb, tb};
        int n = 2;
        const double ds = d.x / hf_.dx - d.y / hf_.dy;  // d(s - r)/dt
        if (ds != 0.0) {
            const double s0 = (o.x - xi) / hf_.dx - (o.y - yj) / hf_.dy;
            const double tk = -s0 / ds;
            if (tk > ta && tk < tb) {
                ts[1] = tk;
                ts[2] = tb;
                n = 3;
            }
        }
        double g_prev = gap(ts[0]);
        under = under && g_prev <= 0.0;
        if (!under && g_prev <= 0.0) {
            hit = ts[0];
            return false;
        }
        for (int k = 1; k < n; ++k) {
            const double g = gap(ts[k]);
            if (under) {  // still beneath the surface it entered under
                under = g <= 0.0;
                g_prev = g;
                continue;
            }
            if (g <= 0.0) {  // linear on this piece: the crossing is exact
                hit = ts[k - 1] + (ts[k] - ts[k - 1]) * g_prev / (g_prev - g);
                return false;
            }
            g_prev = g;
        }
        return true;
    });
    return hit;
}

glm::dvec3 HeightfieldRay::normal(double x, double y) const
{
    if (hf_.nx < 2 || hf_.ny < 2)
        return {0.0, 0.0, 1.0};
    const double gx = std::clamp((x - hf_.x0) / hf_.dx, 0.0, double(hf_.nx - 1));
    const double gy = std::clamp((y - hf_.y0) / hf_.dy, 0.0, double(hf_.ny - 1));
    const int i = std::min(int(gx), hf_.nx - 2), j = std::min(int(gy), hf_.ny - 2);
    const double s = gx - i, r = gy - j;
    const double z00 = hf_.at(i, j), z11 = hf_.at(i + 1, j + 1);
    double zx, zy;
    if (s >= r) {
        zx = (hf_.at(i + 1, j) - z00) / hf_.dx;
        zy = (z11 - hf_.at(i + 1, j)) / hf_.dy;
    } else {
        zy = (hf_.at(i, j + 1) - z00) / hf_.dy;
        zx = (z11 - hf_.at(i, j + 1)) / hf_.dx;
    }
    return glm::normalize(glm::dvec3(-zx, -zy, 1.0));
}

}  // namespace kiri::geometry::detail
