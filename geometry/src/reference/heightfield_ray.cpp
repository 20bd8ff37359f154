#include "reference/heightfield_ray.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>

namespace kiri::geometry::detail {

HeightfieldRay::HeightfieldRay(const Heightfield& hf, bool surround)
    : hf_(hf), ground_(hf, surround), frame_{hf.x0, hf.y0, hf.dx, hf.dy, hf.nx, hf.ny}
{
    top_ = surround ? std::max(ground_.z_max(), ground_.base()) : ground_.z_max();
}

double HeightfieldRay::cell_height(int i, int j, double s, double r) const
{
    s = std::clamp(s, 0.0, 1.0);
    r = std::clamp(r, 0.0, 1.0);
    const double z00 = ground_.sample(i, j), z11 = ground_.sample(i + 1, j + 1);
    if (s >= r)
        return z00 + s * (ground_.sample(i + 1, j) - z00) + r * (z11 - ground_.sample(i + 1, j));
    return z00 + r * (ground_.sample(i, j + 1) - z00) + s * (z11 - ground_.sample(i, j + 1));
}

std::optional<double> HeightfieldRay::first_hit(const glm::dvec3& o, const glm::dvec3& d, double t0, double t1) const
{
    if (hf_.nx < 2 || hf_.ny < 2)
        return std::nullopt;
    // A hit needs z <= the ground's top: clip the segment to that slab first (rays towards the
    // sun leave it quickly, so shadow queries stay short).
    const double t_start = t0;
    if (!clip_slab(o.z, d.z, -inf, top_, t0, t1))
        return std::nullopt;
    if (!ground_.surround()) {
        // A ray from outside the grid that enters it under the terrain's edge passes beneath the
        // surface, as the bare tile (a surface, not a solid) is drawn: the grid's edge is no wall.
        const bool outside = o.x < hf_.x0 || o.x > hf_.x_max() || o.y < hf_.y0 || o.y > hf_.y_max();
        // Where the ray enters the grid's footprint: before the slab (from above) it cannot be under.
        double t_enter = t_start;
        for (const auto [p, v, lo, hi] : {std::array<double, 4>{o.x, d.x, hf_.x0, hf_.x_max()},
                                          std::array<double, 4>{o.y, d.y, hf_.y0, hf_.y_max()}})
            if (v != 0.0)
                t_enter = std::max(t_enter, std::min((lo - p) / v, (hi - p) / v));
        return grid_hit(o, d, t0, t1, outside && t_enter >= t0);
    }
    // The surround is continuous with the grid's edge: a ray reaching the edge under the ground
    // has met the surround before, so the grid is entered from above.
    double fa = t0, fb = t1;
    if (!clip_slab(o.x, d.x, hf_.x0, hf_.x_max(), fa, fb) || !clip_slab(o.y, d.y, hf_.y0, hf_.y_max(), fa, fb))
        return surround_hit(o, d, t0, t1);
    if (fa > t0)
        if (const auto hit = surround_hit(o, d, t0, fa))
            return hit;
    if (const auto hit = grid_hit(o, d, fa, fb, false))
        return hit;
    return fb < t1 ? surround_hit(o, d, fb, t1) : std::nullopt;
}

std::optional<double> HeightfieldRay::grid_hit(const glm::dvec3& o, const glm::dvec3& d, double t0, double t1,
                                               bool under_at_entry) const
{
    std::optional<double> hit;
    bool under = under_at_entry;
    walk_grid(frame_, o, d, t0, t1, [&](int i, int j, double ta, double tb) {
        // Above the cell's highest corner over all of [ta, tb]: above its two triangles too.
        if (!under &&
            std::min(o.z + d.z * ta, o.z + d.z * tb) >
                std::max(std::max(ground_.sample(i, j), ground_.sample(i + 1, j)),
                         std::max(ground_.sample(i, j + 1), ground_.sample(i + 1, j + 1))))
            return true;
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

std::optional<double> HeightfieldRay::surround_hit(const glm::dvec3& o, const glm::dvec3& d, double t0, double t1) const
{
    const double base = ground_.base();
    // Where the ground is flat at the base (beyond the eased band): the plane's crossing.
    const auto plane = [&](double a, double b) -> std::optional<double> {
        if (!(b >= a))
            return std::nullopt;
        if (o.z + d.z * a <= base)
            return a;
        if (d.z < 0.0) {
            const double t = (base - o.z) / d.z;
            if (t >= a && t <= b)
                return t;
        }
        return std::nullopt;
    };
    // The eased band lies inside the grid's rectangle grown by the ease distance.
    const double e = ground_.ease();
    double ea = t0, eb = t1;
    if (!clip_slab(o.x, d.x, hf_.x0 - e, hf_.x_max() + e, ea, eb) ||
        !clip_slab(o.y, d.y, hf_.y0 - e, hf_.y_max() + e, ea, eb))
        return plane(t0, t1);
    if (ea > t0)
        if (const auto hit = plane(t0, ea))
            return hit;
    const auto gap = [&](double t) {
        const glm::dvec3 p = o + d * t;
        return p.z - ground_.height(p.x, p.y);
    };
    double t = ea, g = gap(t);
    if (g <= 0.0)
        return t;
    const double horizontal = std::hypot(d.x, d.y);
    if (horizontal == 0.0) {  // a vertical ray: the ground's height is constant along it
        const double hit = t - g / d.z;
        return d.z < 0.0 && hit <= eb ? std::optional<double>(hit) : std::nullopt;
    }
    // Steps of a cell at the edge (the edge's detail), longer further out where the surround
    // is smoother; a crossing is bisected to the double's precision.
    const double cell = std::min(hf_.dx, hf_.dy);
    while (t < eb) {
        const glm::dvec3 p = o + d * t;
        const double tn = std::min(eb, t + (cell + ground_.distance_outside(p.x, p.y) / 16.0) / horizontal);
        const double gn = gap(tn);
        if (gn <= 0.0) {
            double lo = t, hi = tn, g_lo = g, g_hi = gn;
            for (int k = 0; k < 60 && hi - lo > 1e-12 * std::max(1.0, hi); ++k) {
                const double mid = lo + (hi - lo) * std::clamp(g_lo / (g_lo - g_hi), 0.05, 0.95);
                const double gm = gap(mid);
                (gm <= 0.0 ? hi : lo) = mid;
                (gm <= 0.0 ? g_hi : g_lo) = gm;
            }
            return hi;
        }
        t = tn;
        g = gn;
    }
    return eb < t1 ? plane(eb, t1) : std::nullopt;
}

}  // namespace kiri::geometry::detail
