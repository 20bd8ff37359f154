// One particle's effect on the light (particle_footprint.hpp): the profile, its area, the light
// gain of Shimada (7) in its saturating form, the clamp for opaque particles, and the forward
// fraction of Henyey-Greenstein scattering.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "kiri/geometry/medium/medium.hpp"
#include "kiri/geometry/particles/particle_footprint.hpp"
#include "kiri/geometry/particles/particles.hpp"

using namespace kiri::geometry;

TEST(ParticleFootprint, ProfileIsAGaussianReachingZeroAtTheRim)
{
    EXPECT_DOUBLE_EQ(footprint_profile(0.0), 1.0);
    EXPECT_NEAR(footprint_profile(1.0 - 1e-12), 0.0, 1e-11);
    EXPECT_EQ(footprint_profile(1.0), 0.0);
    EXPECT_EQ(footprint_profile(7.0), 0.0);
    EXPECT_EQ(footprint_profile(std::nan("")), 0.0);
    // Shape: (g(x) - g(1)) / (1 - g(1)) with g the Gaussian of sigma 0.4.
    const auto g = [](double x) { return std::exp(-x * x / (2.0 * 0.16)); };
    for (double x : {0.1, 0.4, 0.75})
        EXPECT_NEAR(footprint_profile(x), (g(x) - g(1.0)) / (1.0 - g(1.0)), 1e-15);
    for (double x = 0.0; x < 1.0; x += 0.01)
        EXPECT_GT(footprint_profile(x), footprint_profile(x + 0.01));
}

TEST(ParticleFootprint, AreaIsTheIntegralOfTheProfile)
{
    // 2 pi int_0^1 f(x) x dx by Simpson's rule.
    const int n = 20000;
    double sum = 0.0;
    for (int k = 0; k <= n; ++k) {
        const double x = double(k) / n * (1.0 - 1e-15);
        sum += (k == 0 || k == n ? 1.0 : k % 2 ? 4.0 : 2.0) * footprint_profile(x) * x;
    }
    EXPECT_NEAR(2.0 * std::numbers::pi * sum / (3.0 * n), footprint_area(), 1e-9);
    EXPECT_NEAR(footprint_area(), 0.861, 1e-3);
}

TEST(ParticleFootprint, LogGainIsShimadasGainSaturated)
{
    const double r = 10.0, tau = 0.7, a = 0.9, c = 0.25;
    for (double rho : {0.0, 3.0, 8.0}) {
        const double t = std::exp(-tau * footprint_profile(rho / r));
        EXPECT_NEAR(footprint_log_gain(rho, r, tau, a, c), std::log(t + a * c * (1.0 - t)), 1e-14);
        EXPECT_NEAR(footprint_transmittance(rho, r, tau), t, 1e-15);
    }
    // Optically thin: G -> 1 - tau f (1 - a c), Shimada's a tau c + T to first order.
    const double thin = 1e-6;
    EXPECT_NEAR(footprint_log_gain(0.0, r, thin, a, c), -thin * (1.0 - a * c), 1e-12);
    // Outside the disc and for empty particles: no effect.
    EXPECT_EQ(footprint_log_gain(r, r, tau, a, c), 0.0);
    EXPECT_EQ(footprint_log_gain(1.0, r, 0.0, a, c), 0.0);
    EXPECT_EQ(footprint_log_gain(1.0, 0.0, tau, a, c), 0.0);
    // Never above 1: a particle does not add light, even very thick and white.
    for (double t : {0.1, 1.0, 5.0, 50.0, 1e6})
        EXPECT_LE(footprint_log_gain(0.0, r, t, 1.0, 0.5), 0.0);
}

TEST(ParticleFootprint, RayShareIsTheParticlesDensityIntegratedAlongTheRay)
{
    // The particle in three dimensions: k(q) = exp(-q^2 / 2 (s r)^2) - e0 for q < r. Along a ray
    // passing rho from the centre, q^2 = rho^2 + u^2; integrated by Simpson's rule.
    const double r = 50.0, s = 0.4 * r, e0 = std::exp(-1.0 / (2.0 * 0.16));
    const auto k = [&](double rho, double u) {
        return std::max(std::exp(-(rho * rho + u * u) / (2.0 * s * s)) - e0, 0.0);
    };
    const auto integral = [&](double rho, double a, double b) {
        const int n = 4000;
        double sum = 0.0;
        for (int i = 0; i <= n; ++i)
            sum += (i == 0 || i == n ? 1.0 : i % 2 ? 4.0 : 2.0) * k(rho, a + (b - a) * i / n);
        return sum * (b - a) / (3.0 * n);
    };
    for (double x : {0.0, 0.3, 0.7, 0.95}) {
        const double half = r * std::sqrt(1.0 - x * x), whole = integral(x * r, -half, half);
        for (const auto& [u0, u1] : {std::pair{-half, 0.2 * half}, {-0.4 * half, 0.9 * half}, {0.5 * half, 2.0 * r}})
            EXPECT_NEAR(footprint_ray_share(x, r, u0, u1), integral(x * r, u0, std::min(u1, half)) / whole, 1e-7)
                << x << " " << u0 << " " << u1;
    }
    // The whole chord, half of it by symmetry, none of it; beyond the rim nothing.
    EXPECT_NEAR(footprint_ray_share(0.4, r, -1e9, 1e9), 1.0, 1e-14);
    EXPECT_NEAR(footprint_ray_share(0.4, r, 0.0, 1e9), 0.5, 1e-14);
    EXPECT_NEAR(footprint_ray_share(0.4, r, -1e9, 0.0), 0.5, 1e-14);
    EXPECT_EQ(footprint_ray_share(0.4, r, 10.0, 10.0), 0.0);
    EXPECT_EQ(footprint_ray_share(0.4, r, 10.0, -10.0), 0.0);
    EXPECT_EQ(footprint_ray_share(1.0, r, -1e9, 1e9), 0.0);
    // At the rim, where the integral cancels, by length; never NaN.
    EXPECT_NEAR(footprint_ray_share(1.0 - 1e-14, r, 0.0, 1e9), 0.5, 1e-6);
    EXPECT_EQ(footprint_ray_share(std::nan(""), r, 0.0, 1.0), 0.0);
    EXPECT_EQ(footprint_ray_share(0.2, r, std::nan(""), 1.0), 0.0);
    EXPECT_EQ(footprint_ray_share(0.2, 0.0, -1.0, 1.0), 0.0);
}

TEST(ParticleFootprint, OpaqueParticlesGiveFiniteLogGains)
{
    const double inf = std::numeric_limits<double>::infinity();
    // Black and opaque: G = 0, clamped.
    EXPECT_EQ(footprint_log_gain(0.0, 5.0, inf, 0.0, 0.3), min_log_gain);
    EXPECT_EQ(footprint_log_gain(2.0, 5.0, 1e300, 0.0, 0.3), min_log_gain);
    // White and opaque: G = a c, what it scatters forward.
    EXPECT_NEAR(footprint_log_gain(0.0, 5.0, inf, 1.0, 0.3), std::log(0.3), 1e-15);
    EXPECT_NEAR(footprint_log_gain(1.0, 5.0, 1e5, 0.8, 0.3), std::log(0.24), 1e-15);
    EXPECT_EQ(footprint_transmittance(0.0, 5.0, inf), 0.0);
    // At the rim an infinite optical depth is still nothing (0 * inf must not be NaN).
    EXPECT_EQ(footprint_log_gain(5.0, 5.0, inf, 0.0, 0.3), 0.0);
    EXPECT_EQ(footprint_transmittance(5.0, 5.0, inf), 1.0);
}

TEST(ParticleFootprint, ForwardFractionIsHenyeyGreensteinOverTheCone)
{
    // Isotropic: the cone's share of the sphere.
    EXPECT_NEAR(forward_scattering_fraction(0.0, 0.09), 0.09 / (4.0 * std::numbers::pi), 1e-15);
    EXPECT_NEAR(forward_scattering_fraction(0.0, 4.0 * std::numbers::pi), 1.0, 1e-15);
    for (double g : {-0.5, 0.3, 0.8, 0.95}) {
        // 2 pi int_mu0^1 p(mu) dmu by Simpson's rule.
        const double omega = 0.09, mu0 = 1.0 - omega / (2.0 * std::numbers::pi);
        const int n = 2000;
        double sum = 0.0;
        for (int k = 0; k <= n; ++k)
            sum += (k == 0 || k == n ? 1.0 : k % 2 ? 4.0 : 2.0) * henyey_greenstein(mu0 + (1.0 - mu0) * k / n, g);
        EXPECT_NEAR(forward_scattering_fraction(g, omega), 2.0 * std::numbers::pi * sum * (1.0 - mu0) / (3.0 * n), 1e-9)
            << g;
    }
    EXPECT_NEAR(forward_scattering_fraction(0.8), 0.228, 1e-3);
    // The whole sphere holds all of it, whatever g.
    EXPECT_NEAR(forward_scattering_fraction(0.8, 4.0 * std::numbers::pi), 1.0, 1e-12);
}

TEST(ParticleFootprint, ShareAboveTheGroundIsTheBallsMassOverIt)
{
    // Over a flat ground z0 r from the centre, by horizontal slices (an independent route: the
    // columns of footprint_share_above cut vertically): the slice at z holds
    // 2 pi (s^2 (exp(-z^2 / 2 s^2) - e0) - e0 (1 - z^2) / 2).
    const double s = footprint_sigma, e0 = std::exp(-1.0 / (2.0 * s * s));
    const auto slice = [&](double z) {
        return 2.0 * std::numbers::pi * (s * s * (std::exp(-z * z / (2.0 * s * s)) - e0) - 0.5 * e0 * (1.0 - z * z));
    };
    const auto above = [&](double z0) {  // Simpson's rule from z0 to 1 over -1 to 1
        const auto integral = [&](double a, double b) {
            const int n = 4000;
            double sum = 0.0;
            for (int k = 0; k <= n; ++k)
                sum += (k == 0 || k == n ? 1.0 : k % 2 ? 4.0 : 2.0) * slice(a + (b - a) * k / n);
            return sum * (b - a) / (3.0 * n);
        };
        return integral(z0, 1.0) / integral(-1.0, 1.0);
    };
    const glm::dvec3 centre(100.0, -40.0, 250.0);
    const double r = 80.0;
    for (double z0 : {-0.9, -0.5, -0.2, 0.0, 0.3, 0.7}) {
        const double share = footprint_share_above(centre, r, [&](double, double) { return centre.z + z0 * r; });
        EXPECT_NEAR(share, above(z0), 2e-3) << z0;
    }
    EXPECT_NEAR(above(0.0), 0.5, 1e-12);
    // Wholly above or below.
    EXPECT_EQ(footprint_share_above(centre, r, [&](double, double) { return centre.z - r; }), 1.0);
    EXPECT_EQ(footprint_share_above(centre, r, [&](double, double) { return centre.z + r; }), 0.0);
    // Any plane through the centre, and a cliff through it, halve the ball: the ground's relief
    // within the disc counts, not only its height under the centre.
    for (double slope : {0.3, 1.0, 5.0})
        EXPECT_NEAR(footprint_share_above(
                        centre, r,
                        [&](double x, double y) { return centre.z + slope * ((x - centre.x) + 0.5 * (y - centre.y)); }),
                    0.5, 1e-12)
            << slope;
    const double cliff = footprint_share_above(
        centre, r, [&](double x, double y) { return (x - centre.x) + 0.37 * (y - centre.y) < 0.0 ? 1e9 : -1e9; });
    EXPECT_NEAR(cliff, 0.5, 1e-12);
    // A narrow valley 0.4 r wide through the centre, its walls above the particle: most of the
    // ball lies in the walls (the height under the centre alone would say none).
    const double valley = footprint_share_above(
        centre, r, [&](double x, double) { return std::abs(x - centre.x) < 0.2 * r ? centre.z - r : centre.z + r; });
    EXPECT_GT(valley, 0.3);
    EXPECT_LT(valley, 0.6);
    // Nothing known: no ground (NaN heights), and no particle to speak of.
    EXPECT_EQ(footprint_share_above(centre, r, [](double, double) { return std::nan(""); }), 1.0);
    EXPECT_EQ(footprint_share_above(centre, 0.0, [&](double, double) { return centre.z + r; }), 1.0);
    EXPECT_EQ(footprint_share_above({std::nan(""), 0.0, 0.0}, r, [](double, double) { return 0.0; }), 1.0);
}

TEST(ParticleFootprint, ShareBetweenAFloorAndATopIsTheBallsMassBetweenThem)
{
    // Between level planes zb r and zt r from the centre, by horizontal slices as above (an
    // independent route): a fog lake's top over the particle, a blanket's floor under it.
    const double s = footprint_sigma, e0 = std::exp(-1.0 / (2.0 * s * s));
    const auto slice = [&](double z) {
        return 2.0 * std::numbers::pi * (s * s * (std::exp(-z * z / (2.0 * s * s)) - e0) - 0.5 * e0 * (1.0 - z * z));
    };
    const auto integral = [&](double a, double b) {  // Simpson's rule
        const int n = 4000;
        double sum = 0.0;
        for (int k = 0; k <= n; ++k)
            sum += (k == 0 || k == n ? 1.0 : k % 2 ? 4.0 : 2.0) * slice(a + (b - a) * k / n);
        return sum * (b - a) / (3.0 * n);
    };
    const glm::dvec3 centre(-300.0, 75.0, 480.0);
    const double r = 60.0, nan = std::nan("");
    const auto between = [&](double lo, double hi) {
        return footprint_share_between(centre, r, [&](double, double) { return std::pair{lo, hi}; });
    };
    for (const auto& [zb, zt] : {std::pair{-0.8, 0.2}, {-0.3, 0.4}, {0.1, 0.6}, {-1.0, -0.4}}) {
        EXPECT_NEAR(between(centre.z + zb * r, centre.z + zt * r), integral(zb, zt) / integral(-1.0, 1.0), 2e-3)
            << zb << " .. " << zt;
    }
    // A top through the centre halves it, and a top alone is the ground's complement.
    EXPECT_NEAR(between(nan, centre.z), 0.5, 1e-12);
    EXPECT_NEAR(between(nan, centre.z + 0.3 * r),
                1.0 - footprint_share_above(centre, r, [&](double, double) { return centre.z + 0.3 * r; }), 1e-12);
    // No bounds: the whole; a top under the floor: none.
    EXPECT_EQ(between(nan, nan), 1.0);
    EXPECT_EQ(between(centre.z + 0.2 * r, centre.z - 0.2 * r), 0.0);
    // A top sloping through the centre halves it too, whatever its slope.
    for (double slope : {0.2, 1.5})
        EXPECT_NEAR(footprint_share_between(centre, r,
                                            [&](double x, double) {
                                                return std::pair{nan, centre.z + slope * (x - centre.x)};
                                            }),
                    0.5, 1e-12)
            << slope;
}
