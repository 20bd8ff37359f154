// [Thesis] (2.6)-(2.10), each exactly as printed or as docs/references.md reads it.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "kiri/geometry/layers/layer_stack.hpp"

namespace kiri::geometry {

double layer_spacing(double eye_distance, double divisor) { return eye_distance / divisor; }

double layer_alpha(double i, double l)
{
    if (!(l > 0.0))
        return 1.0;  // the base alone
    return 1.0 - 0.9 * i / l;
}

double narrowed_spacing(double r0, double moved, double reference_distance)
{
    if (!(reference_distance > 0.0))
        return 0.0;  // the reference eye sits at O: nothing left to narrow
    const double fraction = std::clamp(moved / reference_distance, 0.0, 1.0);
    return r0 * (1.0 - fraction);
}

double layer_scale(double k, double sin_theta, double rate) { return 1.0 + k * rate * sin_theta; }

double elevation_angle(const glm::dvec3& eye, const glm::dvec3& point, const glm::dvec3& normal)
{
    const glm::dvec3 d = eye - point;
    const double length = glm::length(d);
    if (!(length > 0.0) || !std::isfinite(length))
        return 0.0;
    const double s = std::min(std::abs(glm::dot(normal, d)) / length, 1.0);
    return std::asin(s);
}

}  // namespace kiri::geometry
