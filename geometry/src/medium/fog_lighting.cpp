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

int scattering_octaves_of(const Medium* medium)
{
    return std::clamp(medium ? medium->options().scattering_octaves : MediumOptions{}.scattering_octaves, 1, 8);
}

}  // namespace kiri::geometry
