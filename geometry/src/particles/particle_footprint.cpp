#include "kiri/geometry/particles/particle_footprint.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "kiri/geometry/particles/particles.hpp"

namespace kiri::geometry {
namespace {

const double e0 = std::exp(-1.0 / (2.0 * footprint_sigma * footprint_sigma));

// The integral of k along a ray at x = rho / r from u = 0 to u (|u| within the half chord),
// in units where the radius is 1: sqrt(pi / 2) s g erf(u / (s sqrt 2)) - e0 u, g = exp(-x^2 / 2s^2).
double chord_integral(double x, double u)
{
    const double s = footprint_sigma;
    const double g = std::exp(-x * x / (2.0 * s * s));
    return std::sqrt(std::numbers::pi / 2.0) * s * g * std::erf(u / (s * std::numbers::sqrt2)) - e0 * u;
}

// The part of the chord at x = rho / r between u0 and u1 (metres from its point nearest the centre),
// in units of the radius and within the half chord: [a, b], and the half chord. False when the
// ray misses the ball or the part is empty.
bool chord_part(double& x, double radius, double u0, double u1, double& a, double& b, double& half)
{
    if (!(x < 1.0) || !(radius > 0.0) || std::isnan(u0) || std::isnan(u1))
        return false;
    x = std::max(x, 0.0);
    half = std::sqrt(1.0 - x * x);
    a = std::clamp(u0 / radius, -half, half);
    b = std::clamp(u1 / radius, -half, half);
    return b > a;
}

}  // namespace

double footprint_profile(double x)
{
    if (!(x < 1.0))  // also NaN
        return 0.0;
    x = std::max(x, 0.0);
    return (std::exp(-x * x / (2.0 * footprint_sigma * footprint_sigma)) - e0) / (1.0 - e0);
}

double ball_density(double q, double radius, double optical_depth)
{
    if (!(radius > 0.0) || !(q < radius) || !(optical_depth > 0.0))
        return 0.0;
    const double x = q / radius;
    const double k = std::exp(-x * x / (2.0 * footprint_sigma * footprint_sigma)) - e0;
    return k > 0.0 ? optical_depth * k / (radius * 2.0 * chord_integral(0.0, 1.0)) : 0.0;
}

double ball_mass()
{
    // 4 pi int_0^1 q^2 (exp(-q^2 / 2s^2) - e0) dq over the centre's column 2 chord_integral(0, 1).
    const double sg = footprint_sigma;
    const double inner =
        sg * sg * (sg * std::sqrt(std::numbers::pi / 2.0) * std::erf(1.0 / (sg * std::numbers::sqrt2)) - e0) - e0 / 3.0;
    return 4.0 * std::numbers::pi * inner / (2.0 * chord_integral(0.0, 1.0));
}

double ball_chord_share(double x, double radius, double u0, double u1)
{
    double a, b, half;
    if (!chord_part(x, radius, u0, u1, a, b, half))
        return 0.0;
    return std::max(chord_integral(x, b) - chord_integral(x, a), 0.0) / (2.0 * chord_integral(0.0, 1.0));
}

double footprint_area()
{
    // 2 pi int_0^1 f(x) x dx with int_0^1 exp(-x^2 / 2s^2) x dx = s^2 (1 - e0), int_0^1 e0 x dx = e0 / 2.
    const double s2 = footprint_sigma * footprint_sigma;
    return 2.0 * std::numbers::pi * (s2 * (1.0 - e0) - 0.5 * e0) / (1.0 - e0);
}

double footprint_log_gain(double rho, double radius, double optical_depth, double albedo, double forward)
{
    if (!(radius > 0.0) || !(optical_depth > 0.0))
        return 0.0;
    const double f = footprint_profile(rho / radius);
    if (f <= 0.0)
        return 0.0;  // outside the disc: 0, never 0 * inf
    const double t = optical_depth * f;
    const double ac = std::clamp(albedo, 0.0, 1.0) * std::clamp(forward, 0.0, 1.0);
    // log(T + ac (1 - T)) = -t + log(1 + ac (e^t - 1)); written with expm1 / log1p so a thin
    // particle keeps its digits and a thick one does not overflow.
    double g;
    if (ac <= 0.0)
        g = -t;
    else if (t > 700.0)
        g = std::log(ac);
    else
        g = -t + std::log1p(ac * std::expm1(t));
    return std::clamp(std::isnan(g) ? min_log_gain : g, min_log_gain, 0.0);
}

double footprint_transmittance(double rho, double radius, double optical_depth)
{
    if (!(radius > 0.0) || !(optical_depth > 0.0))
        return 1.0;
    const double f = footprint_profile(rho / radius);
    return f <= 0.0 ? 1.0 : std::exp(-optical_depth * f);
}

double footprint_ray_share(double x, double radius, double u0, double u1)
{
    double a, b, half;
    if (!chord_part(x, radius, u0, u1, a, b, half))
        return 0.0;
    const double whole = 2.0 * chord_integral(x, half);
    // At the rim the density along so short a chord is nearly even, and the integral is lost to
    // cancellation: share by length there.
    if (!(whole > 1e-12))
        return (b - a) / (2.0 * half);
    return std::clamp((chord_integral(x, b) - chord_integral(x, a)) / whole, 0.0, 1.0);
}

double footprint_share_above(const glm::dvec3& centre, double radius,
                             const std::function<double(double, double)>& ground)
{
    return footprint_share_between(centre, radius, [&](double x, double y) {
        return std::pair{ground(x, y), std::numeric_limits<double>::quiet_NaN()};
    });
}

double footprint_share_between(const glm::dvec3& centre, double radius,
                               const std::function<std::pair<double, double>(double, double)>& slab)
{
    if (!(radius > 0.0) || !std::isfinite(radius) || !std::isfinite(centre.x) || !std::isfinite(centre.y) ||
        !std::isfinite(centre.z))
        return 1.0;
    // Rings at the midpoints of 8 equal steps of x = rho / r, 12 angles each (turned half a step
    // every other ring); a column at x holds 2 chord_integral(x, w) over its half chord w, and
    // the part of it between z_b and z_t (metres from the centre over r, each clamped to
    // [-w, w]) chord_integral(x, z_t) - chord_integral(x, z_b).
    constexpr int rings = 8, angles = 12;
    double whole = 0.0, within = 0.0;
    for (int i = 0; i < rings; ++i) {
        const double x = (i + 0.5) / rings, w = std::sqrt(1.0 - x * x);
        const double half_column = chord_integral(x, w);
        if (!(half_column > 0.0))
            continue;
        for (int k = 0; k < angles; ++k) {
            const double phi = 2.0 * std::numbers::pi * (k + 0.5 * (i % 2)) / angles;
            const auto [lo, hi] = slab(centre.x + radius * x * std::cos(phi), centre.y + radius * x * std::sin(phi));
            const double zb = std::isnan(lo) ? -w : std::clamp((lo - centre.z) / radius, -w, w);
            const double zt = std::isnan(hi) ? w : std::clamp((hi - centre.z) / radius, -w, w);
            whole += x * 2.0 * half_column;
            if (zt > zb)
                within += x * (chord_integral(x, zt) - chord_integral(x, zb));
        }
    }
    return whole > 0.0 ? std::clamp(within / whole, 0.0, 1.0) : 1.0;
}

double mass_gain(double share) { return 1.0 / std::clamp(std::isnan(share) ? 1.0 : share, min_share_drawn, 1.0); }

double forward_scattering_fraction(double g, double solid_angle)
{
    const double omega = std::clamp(std::isfinite(solid_angle) ? solid_angle : 0.0, 0.0, 4.0 * std::numbers::pi);
    g = std::isfinite(g) ? std::clamp(g, -0.999, 0.999) : 0.0;
    if (std::abs(g) < 1e-6)
        return omega / (4.0 * std::numbers::pi);
    const double mu0 = 1.0 - omega / (2.0 * std::numbers::pi);
    const double fraction =
        (1.0 - g * g) / (2.0 * g) * (1.0 / (1.0 - g) - 1.0 / std::sqrt(1.0 + g * g - 2.0 * g * mu0));
    return std::clamp(fraction, 0.0, 1.0);
}

}  // namespace kiri::geometry
