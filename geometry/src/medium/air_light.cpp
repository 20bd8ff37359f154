#include "kiri/geometry/medium/air_light.hpp"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

namespace kiri::geometry {

double AirLight::haze(double distance) const
{
    const double x = extinction * distance;
    return x > 0.0 && std::isfinite(x) ? -std::expm1(-x) : (x > 0.0 ? 1.0 : 0.0);
}

glm::dvec3 AirLight::seen(const glm::dvec3& radiance_at_point, double distance) const
{
    const double h = haze(distance);
    return h > 0.0 ? radiance_at_point * (1.0 - h) + radiance * h : radiance_at_point;
}

glm::dvec3 sky_horizon(const glm::dvec3& ambient) { return glm::mix(ambient * 3.0, glm::dvec3(1.0), 0.3); }

AirLight scene_air(double across, const glm::dvec3& ambient, bool sky)
{
    if (!sky)
        return {};
    const double reach = std::isfinite(across) ? std::max(150000.0, 3.0 * across) : 150000.0;
    return {1.0 / reach, sky_horizon(ambient)};
}

}  // namespace kiri::geometry
