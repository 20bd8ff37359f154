// The exact Harris light pass (harris_reference.hpp): one particle, two on a line to the sun,
// the recurrence order, the index against every pair, a slab against Beer-Lambert, opaque
// particles, and lights along an axis and a diagonal.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "kiri/geometry/particles/harris_reference.hpp"
#include "kiri/geometry/particles/particle_footprint.hpp"
#include "particle_test_clouds.hpp"

using namespace kiri::geometry;

namespace {

double log_gain(const Particle& p, double rho, double c)
{
    return footprint_log_gain(rho, p.radius, p.optical_depth, p.albedo, c);
}

}  // namespace

TEST(HarrisReference, OneParticleIsFullyLit)
{
    ParticleCloud c;
    c.particles = {{{3.0, 4.0, 5.0}, 10.0, 2.0, 0.9}};
    EXPECT_EQ(harris_light_pass(c, {0.3, 0.1, 1.0}), std::vector<double>{1.0});
}

TEST(HarrisReference, TwoParticlesOnALineToTheSun)
{
    // The sun along (1, 2, 2) / 3; b lies 50 m down-sun of a.
    const glm::dvec3 light = glm::dvec3(1.0, 2.0, 2.0) / 3.0;
    ParticleCloud c;
    c.forward_scattering = 0.2;
    const Particle a{{10.0, 0.0, 100.0}, 8.0, 1.5, 0.9};
    const Particle b{a.position - 50.0 * light, 6.0, 0.7, 0.5};
    c.particles = {b, a};  // input order does not matter
    const std::vector<double> g = harris_light_pass(c, light);
    EXPECT_EQ(g[1], 1.0);
    // (3)-(4): I = a c (1 - T) + T with T = exp(-tau) at the centre of a's footprint.
    const double t = std::exp(-1.5);
    EXPECT_NEAR(g[0], 0.9 * 0.2 * (1.0 - t) + t, 1e-15);
    EXPECT_NEAR(std::log(g[0]), log_gain(a, 0.0, 0.2), 1e-14);
    // Moved 5 m sideways: a's footprint at rho = 5.
    c.particles[0].position += 5.0 * glm::normalize(glm::cross(light, glm::dvec3(0.0, 0.0, 1.0)));
    EXPECT_NEAR(std::log(harris_light_pass(c, light)[0]), log_gain(a, 5.0, 0.2), 1e-13);
    // Beyond a's radius: unshaded.
    c.particles[0].position += 4.0 * glm::normalize(glm::cross(light, glm::dvec3(0.0, 0.0, 1.0)));
    EXPECT_EQ(harris_light_pass(c, light)[0], 1.0);
}

TEST(HarrisReference, RecurrenceAppliesOccludersInSunOrder)
{
    // Three on a vertical line, sun overhead: the lowest gets both products.
    ParticleCloud c;
    c.forward_scattering = 0.3;
    c.particles = {{{0, 0, 0}, 5, 1.0, 0.8}, {{0, 0, 20}, 5, 2.0, 0.6}, {{0, 0, 10}, 5, 0.5, 1.0}};
    const std::vector<double> g = harris_light_pass(c, {0, 0, 1});
    EXPECT_EQ(g[1], 1.0);
    EXPECT_NEAR(g[2], std::exp(log_gain(c.particles[1], 0, 0.3)), 1e-15);
    EXPECT_NEAR(g[0], std::exp(log_gain(c.particles[1], 0, 0.3) + log_gain(c.particles[2], 0, 0.3)), 1e-15);
}

TEST(HarrisReference, IndexEqualsEveryPair)
{
    const ParticleCloud c = kiri::test::ball_cloud(1500, 200.0, 25.0, 0.8);
    HarrisStats stats;
    for (const glm::dvec3& light : {glm::dvec3(0.3, -0.5, 0.8), glm::dvec3(0, 0, 1), glm::dvec3(1, 1, 1)}) {
        const std::vector<double> fast = harris_light_pass(c, light, &stats),
                                  slow = harris_light_pass_quadratic(c, light);
        ASSERT_EQ(fast.size(), slow.size());
        for (std::size_t k = 0; k < fast.size(); ++k)
            ASSERT_EQ(fast[k], slow[k]) << k;
        EXPECT_GT(stats.occluders, 10000u);
        EXPECT_LT(stats.pairs_tested, 1500u * 1500u / 8);  // the index looks at a fraction of the pairs
    }
}

TEST(HarrisReference, UniformSlabFollowsBeerLambert)
{
    // Black particles (a = 0) at random in a slab, sun overhead: log Gamma at depth z has the mean
    // -n z tau r^2 footprint_area() = -sigma z, Beer-Lambert with the particles' extinction.
    std::mt19937_64 rng(5);
    const auto u = [&] { return double(rng() >> 11) * 0x1.0p-53; };
    ParticleCloud c;
    const double side = 400.0, depth = 200.0, r = 10.0, tau = 0.3;
    const int n = 40000;
    for (int k = 0; k < n; ++k)
        c.particles.push_back({{side * u(), side * u(), depth * u()}, r, tau, 0.0});
    const double sigma = n / (side * side * depth) * tau * r * r * footprint_area();
    const std::vector<double> g = harris_light_pass(c, {0, 0, 1});
    // Receivers away from the sides (full footprints above them), binned by depth below the top.
    for (double z0 : {40.0, 100.0, 160.0}) {
        double sum = 0.0;
        int count = 0;
        for (int k = 0; k < n; ++k) {
            const glm::dvec3& p = c.particles[k].position;
            if (p.x > r && p.x < side - r && p.y > r && p.y < side - r && std::abs(depth - p.z - z0) < 10.0) {
                sum += std::log(g[k]);
                ++count;
            }
        }
        EXPECT_NEAR(sum / count, -sigma * z0, 0.03 * sigma * z0) << z0;
    }
}

TEST(HarrisReference, OpaqueParticlesGiveNoNaN)
{
    ParticleCloud c;
    const double inf = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 40; ++k)  // forty opaque black particles stacked
        c.particles.push_back({{0.0, 0.0, 10.0 * k}, 6.0, inf, 0.0});
    const std::vector<double> g = harris_light_pass(c, {0, 0, 1});
    for (int k = 0; k < 40; ++k) {
        EXPECT_TRUE(std::isfinite(g[k]));
        EXPECT_GE(g[k], 0.0);
        EXPECT_LE(g[k], 1.0);
    }
    EXPECT_EQ(g[39], 1.0);
    EXPECT_NEAR(std::log(g[38]), min_log_gain, 1e-12);
}

TEST(HarrisReference, LightAlongAnAxisAndADiagonal)
{
    // A lattice seen along x, along z and along the diagonal: equal spacing, so every particle
    // behind another is shaded by the same footprint centre.
    ParticleCloud c;
    c.forward_scattering = 0.0;
    for (int i = 0; i < 4; ++i)
        c.particles.push_back({glm::dvec3(10.0 * i), 3.0, 0.5, 0.0});
    const std::vector<double> diagonal = harris_light_pass(c, {1, 1, 1});
    for (int i = 0; i < 4; ++i)
        EXPECT_NEAR(std::log(diagonal[i]), -0.5 * (3 - i), 1e-12) << i;
    // Along +x the particles are 10 m apart sideways in y and z: nobody shades anybody.
    for (double g : harris_light_pass(c, {1, 0, 0}))
        EXPECT_EQ(g, 1.0);
    // Along z, a column.
    for (auto& p : c.particles)
        p.position = {0.0, 0.0, p.position.z};
    const std::vector<double> up = harris_light_pass(c, {0, 0, 1});
    for (int i = 0; i < 4; ++i)
        EXPECT_NEAR(std::log(up[i]), -0.5 * (3 - i), 1e-12) << i;
    EXPECT_THROW(harris_light_pass(c, {0, 0, 0}), std::invalid_argument);
}
