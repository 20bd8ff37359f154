#include "kiri/geometry/volume/height_fog.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "kiri/geometry/core/error.hpp"

namespace kiri::geometry {
namespace {

// G(z1) - G(z0) for z0 <= z1, G(z) = integral of sigma from the base to z (linear under the
// base, saturating above it), without cancellation when the two are close.
double cumulative_difference(const HeightFog& f, double z0, double z1)
{
    double sum = 0.0;
    if (z0 < f.base) {  // the constant part under the base
        const double top = std::min(z1, f.base);
        sum += f.extinction * (top - z0);
        z0 = top;
    }
    if (z1 > z0) {  // sigma(z0) H (1 - exp(-(z1 - z0) / H))
        const double dz = z1 - z0;
        sum += f.sigma(z0) * f.scale_height * (std::isinf(dz) ? 1.0 : -std::expm1(-dz / f.scale_height));
    }
    return sum;
}

}  // namespace

double HeightFog::sigma(double z) const
{
    if (!enabled() || std::isnan(z))
        return 0.0;
    return z <= base ? extinction : extinction * std::exp(-(z - base) / scale_height);
}

double HeightFog::sigma(const glm::dvec3& p) const
{
    return p.x >= min.x && p.x <= max.x && p.y >= min.y && p.y <= max.y ? sigma(p.z) : 0.0;
}

double HeightFog::optical_depth(const glm::dvec3& origin, const glm::dvec3& dir, double t0, double t1) const
{
    if (!enabled() || !(t1 > t0))
        return 0.0;
    // Only the part of the segment over the extent.
    for (int axis = 0; axis < 2; ++axis) {
        const double lo = min[axis], hi = max[axis], o = origin[axis], d = dir[axis];
        if (d == 0.0) {
            if (o < lo || o > hi)
                return 0.0;
            continue;
        }
        double a = (lo - o) / d, b = (hi - o) / d;
        if (a > b)
            std::swap(a, b);
        t0 = std::max(t0, a);
        t1 = std::min(t1, b);
    }
    if (!(t1 > t0))
        return 0.0;
    const double speed = std::sqrt(dir.x * dir.x + dir.y * dir.y + dir.z * dir.z);
    const double length_per_z = std::abs(dir.z) > 0.0 ? speed / std::abs(dir.z) : 0.0;
    const double z0 = origin.z + dir.z * t0;
    if (std::isinf(t1)) {
        if (dir.z <= 0.0)
            return std::numeric_limits<double>::infinity();
        return cumulative_difference(*this, z0, std::numeric_limits<double>::infinity()) * length_per_z;
    }
    const double z1 = origin.z + dir.z * t1;
    const double dz = std::abs(z1 - z0);
    // Level (or nearly level) segments: sigma hardly changes, the midpoint rule is exact to
    // O((dz / H)^2) and avoids dividing a difference by a tiny dir.z.
    if (dz < 1e-6 * scale_height)
        return sigma(0.5 * (z0 + z1)) * speed * (t1 - t0);
    return cumulative_difference(*this, std::min(z0, z1), std::max(z0, z1)) * length_per_z;
}

void validate_height_fog(const HeightFog& f, const std::string& label)
{
    check_fields(f, label, "/froxel/height_fog");
    if (!(f.min.x <= f.max.x && f.min.y <= f.max.y))
        throw InputError(label, "/froxel/height_fog/extent", "the minimum must not exceed the maximum");
}

}  // namespace kiri::geometry
