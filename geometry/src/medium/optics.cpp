#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "kiri/geometry/medium/medium.hpp"

namespace kiri::geometry {
namespace {
constexpr double koschmieder = 3.912;  // -ln(0.02): the 2 % contrast threshold
constexpr double water_density_g_per_m3 = 1e6;
constexpr double droplet_extinction_efficiency = 2.0;  // large-particle limit of Mie theory

void require_positive(double v, const char* what)
{
    if (!(v > 0.0) || !std::isfinite(v))
        throw std::invalid_argument(std::string(what) + " must be a finite number > 0");
}
}  // namespace

double visibility_from_extinction(double sigma)
{
    require_positive(sigma, "extinction");
    return koschmieder / sigma;
}

double extinction_from_visibility(double visibility)
{
    require_positive(visibility, "visibility");
    return koschmieder / visibility;
}

double extinction_from_liquid_water(double lwc_g_per_m3, double droplet_radius_um)
{
    require_positive(lwc_g_per_m3, "liquid water content");
    require_positive(droplet_radius_um, "droplet radius");
    return 3.0 * droplet_extinction_efficiency * lwc_g_per_m3 /
        (4.0 * water_density_g_per_m3 * droplet_radius_um * 1e-6);
}

double henyey_greenstein(double cos_theta, double g)
{
    g = std::isfinite(g) ? std::clamp(g, -0.999, 0.999) : 0.0;
    const double c = std::isfinite(cos_theta) ? std::clamp(cos_theta, -1.0, 1.0) : 0.0;
    const double denom = 1.0 + g * g - 2.0 * g * c;  // >= (1 - |g|)^2 > 0
    return (1.0 - g * g) / (4.0 * std::numbers::pi * denom * std::sqrt(denom));
}

}  // namespace kiri::geometry

#include "kiri/geometry/medium/fog_lighting.hpp"

namespace kiri::geometry {

glm::dvec3 fog_source(const FogLight& light, const MediumOptions& optics, double cos_theta, double tau_sun,
                      double visibility)
{
    const double tau = std::isfinite(tau_sun) ? std::max(tau_sun, 0.0) : 0.0;
    const double vis = std::isfinite(visibility) ? std::clamp(visibility, 0.0, 1.0) : 1.0;
    const double sun = sun_scattering(optics.multiple_scattering, optics.scattering_octaves, cos_theta,
                                      optics.anisotropy, optics.albedo, tau, light.sun_elevation_sine);
    const double albedo = std::isfinite(optics.albedo) ? std::clamp(optics.albedo, 0.0, 1.0) : 0.0;
    const glm::dvec3 j = albedo * (std::numbers::pi * vis * sun * light.sun + light.ambient);
    return {std::isfinite(j.x) ? std::max(j.x, 0.0) : 0.0, std::isfinite(j.y) ? std::max(j.y, 0.0) : 0.0,
            std::isfinite(j.z) ? std::max(j.z, 0.0) : 0.0};
}

EngineFog engine_fog(double sigma)
{
    EngineFog e;
    if (!(sigma > 0.0) || !std::isfinite(sigma))
        return e;
    e.hdrp_attenuation_distance_m = 1.0 / sigma;
    e.unreal_fog_density = sigma / (0.1 * std::log(2.0) * std::log(2.0));
    e.godot_density = sigma;
    return e;
}

}  // namespace kiri::geometry
