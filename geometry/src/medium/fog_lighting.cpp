#include "kiri/geometry/medium/fog_lighting.hpp"

#include <algorithm>
#include <cmath>

#include "kiri/geometry/medium/medium.hpp"

namespace kiri::geometry {

double sun_scattering(double cos_theta, double g, double tau_sun, int octaves)
{
    double sum = 0.0, weight = 1.0, depth = std::max(tau_sun, 0.0), eccentricity = g;
    for (int i = 0; i < std::clamp(octaves, 1, 8); ++i) {
        sum += weight * std::exp(-depth) * henyey_greenstein(cos_theta, eccentricity);
        weight *= 0.5;
        depth *= 0.5;
        eccentricity *= 0.5;
    }
    return sum;
}

double fitted_sun_scattering(double cos_theta, double g, double albedo, double tau_sun, double sun_elevation_sine,
                             const MultipleScatteringFit& fit)
{
    const double tau = std::isfinite(tau_sun) ? std::max(tau_sun, 0.0) : 0.0;
    const double a = std::isfinite(albedo) ? std::clamp(albedo, 0.0, 1.0) : 0.0;
    const double b = std::clamp(fit.persistence, 0.0, 1.0) * a;
    const double lobe = std::isfinite(g) ? std::clamp(g, -0.999, 0.999) : 0.0;
    // Order n: exp(-tau) (b tau)^n / n!; the last lobe takes every order from it on, the whole
    // exp(-(1 - b) tau) less the orders before.
    // The light scattered more than once is fed by the sunlight crossing a horizontal plane,
    // which is the sine of the sun's elevation of its beam.
    const double s = std::isfinite(sun_elevation_sine) ? std::clamp(sun_elevation_sine, 0.0, 1.0) : 1.0;
    // The lower the sun, the more of the light scattered a few times still travels its way.
    const double forward = fit.low_sun_eccentricity * (1.0 - s);
    const double c = std::clamp(fit.eccentricity + forward, 0.0, 1.0);
    const double single = std::exp(-tau);
    double multiple = 0.0, weight = single * b * tau, taken = single, eccentricity = lobe * c;
    for (int n = 1; n + 1 < fitted_orders; ++n) {
        multiple += weight * henyey_greenstein(cos_theta, eccentricity);
        taken += weight;
        weight *= b * tau / (n + 1);
        eccentricity *= c;
    }
    const double rest = std::max(std::exp(-(1.0 - b) * tau) - taken, 0.0);
    multiple += rest * henyey_greenstein(cos_theta, std::clamp(fit.diffuse_eccentricity + forward, -1.0, 1.0) * lobe);
    const double sum = single * henyey_greenstein(cos_theta, lobe) +
        fit.amplitude * std::pow(std::max(s, 1e-6), fit.sun_power) * multiple;
    return std::isfinite(sum) ? std::max(sum, 0.0) : 0.0;
}

double sun_scattering(MultipleScattering kind, int octaves, double cos_theta, double g, double albedo, double tau_sun,
                      double sun_elevation_sine, const MultipleScatteringFit& fit)
{
    switch (kind) {
    case MultipleScattering::fitted:
        return fitted_sun_scattering(cos_theta, g, albedo, tau_sun, sun_elevation_sine, fit);
    case MultipleScattering::octaves: return sun_scattering(cos_theta, g, tau_sun, octaves);
    case MultipleScattering::none:
    case MultipleScattering::baked: break;  // the baked volume adds its part where it is read
    }
    return sun_scattering(cos_theta, g, tau_sun, 1);
}

double sun_scattering_decay(MultipleScattering kind, int octaves, const MultipleScatteringFit& fit)
{
    switch (kind) {
    case MultipleScattering::fitted: return std::max(1.0 - std::clamp(fit.persistence, 0.0, 1.0), 1e-3);
    case MultipleScattering::octaves: return std::ldexp(1.0, 1 - std::clamp(octaves, 1, 8));
    case MultipleScattering::none:
    case MultipleScattering::baked: break;
    }
    return 1.0;
}

MultipleScattering multiple_scattering_of(const Medium* medium)
{
    return medium ? medium->options().multiple_scattering : MediumOptions{}.multiple_scattering;
}

int shader_octaves(MultipleScattering kind, int octaves)
{
    if (kind == MultipleScattering::fitted)
        return 0;
    return kind == MultipleScattering::octaves ? std::clamp(octaves, 1, 8) : 1;
}

int shader_octaves(const MediumOptions& optics)
{
    return shader_octaves(optics.multiple_scattering, optics.scattering_octaves);
}

int scattering_octaves_of(const Medium* medium)
{
    return std::clamp(medium ? medium->options().scattering_octaves : MediumOptions{}.scattering_octaves, 1, 8);
}

}  // namespace kiri::geometry
