#include <algorithm>
#include <cmath>
#include <limits>

#include "kiri/geometry/volume/height_fog.hpp"

namespace kiri::geometry {

// Along origin + t dir the height z is linear in t, so the optical depth is an integral over z
// times |dir| / |dir.z|: sigma0 (z1 - z0) under the base, sigma0 H (u(z0) - u(z1)) above it with
// u(z) = exp(-(z - base) / H). Each piece inverts in closed form; every length is measured from
// the piece's start (log1p of a ratio), never as a difference of two altitudes, so the result
// keeps its relative precision for a level ray (dir.z -> 0, where the lengths grow as 1 / dir.z)
// and where u underflows high above the base.
double HeightFog::free_path(const glm::dvec3& origin, const glm::dvec3& dir, double t0, double t1, double depth) const
{
    constexpr double inf = std::numeric_limits<double>::infinity();
    if (!enabled() || !(depth > 0.0) || !(t1 > t0) || std::isnan(t0))
        return inf;
    // Only the part of the segment over the extent (as optical_depth).
    for (int axis = 0; axis < 2; ++axis) {
        const double lo = min[axis], hi = max[axis], o = origin[axis], d = dir[axis];
        if (d == 0.0) {
            if (o < lo || o > hi)
                return inf;
            continue;
        }
        double a = (lo - o) / d, b = (hi - o) / d;
        if (a > b)
            std::swap(a, b);
        t0 = std::max(t0, a);
        t1 = std::min(t1, b);
    }
    if (!(t1 > t0) || !std::isfinite(t0))
        return inf;
    const double speed = std::sqrt(dir.x * dir.x + dir.y * dir.y + dir.z * dir.z);
    if (!(speed > 0.0) || !std::isfinite(speed))
        return inf;
    const double H = scale_height, z0 = origin.z + dir.z * t0;
    double t = t0, rest = depth;
    // The constant part: sigma0 speed per unit t, while z <= base.
    const auto constant = [&](double t_end) {
        const double run = rest / (extinction * speed);
        if (t + run <= t_end)
            return t + run;
        rest -= extinction * speed * (t_end - t);
        t = t_end;
        return inf;
    };
    // The depth per metre of height: tau = (sigma0 H / k) (u(z_a) - u(z_b)), k = |dir.z| / speed.
    const double k = std::abs(dir.z) / speed, per_u = extinction * H / k;
    if (dir.z == 0.0 || !std::isfinite(per_u)) {  // level: sigma is constant along the ray
        const double s = sigma(z0);
        if (!(s > 0.0))
            return inf;
        const double hit = t0 + rest / (s * speed);
        return hit <= t1 ? hit : inf;
    }
    double hit = inf;
    if (dir.z > 0.0) {  // up: the constant part first, then the exponential one
        double z = z0;
        if (z < base) {
            const double t_base = std::min(t1, t0 + (base - z0) / dir.z);
            hit = constant(t_base);
            if (hit < inf)
                return hit;
            if (t >= t1)
                return inf;
            z = base;
        }
        // u falls from u(z) towards 0: rest = per_u u(z) (1 - exp(-dz / H)).
        const double u = std::exp(-(z - base) / H), x = rest / (per_u * u);
        if (!(x < 1.0))
            return inf;
        const double dz = -H * std::log1p(-x);
        hit = t + dz / dir.z;
    } else {  // down: the exponential part first, then the constant one
        if (z0 > base) {
            const double t_base = t0 + (z0 - base) / -dir.z;
            // rest = per_u u(z0) (exp(dz / H) - 1) for a descent dz, up to the base (u = 1).
            const double u = std::exp(-(z0 - base) / H), x = rest / (per_u * u);
            double dz = inf;
            if (std::isfinite(x) && x < 1e300) {
                dz = H * std::log1p(x);
            } else {  // u(z0) underflows: rest = per_u (u(z) - u(z0)) with u(z0) negligible
                dz = (z0 - base) + H * std::log(rest / per_u);
            }
            if (dz < z0 - base) {
                hit = t0 + dz / -dir.z;
                return hit <= t1 ? hit : inf;
            }
            rest -= per_u * -std::expm1(-(z0 - base) / H);
            t = t_base;
            if (!(rest > 0.0))
                return t <= t1 ? t : inf;
        }
        if (t >= t1)
            return inf;
        hit = constant(t1);
    }
    return hit <= t1 ? hit : inf;
}

}  // namespace kiri::geometry
