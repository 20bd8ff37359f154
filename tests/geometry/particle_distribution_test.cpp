// The particles' candidates follow the density they stand for (particles.hpp): d(p), or combined
// rendering's top band d(p) share(h), drawn under the per-cell envelope (shell_envelope.hpp).
// With one candidate per particle nothing is eliminated, so the particles are the candidates;
// their histograms are judged by Pearson's chi-square against the analytic density and against
// an independent sampler (uniform in the Medium's box, kept with probability q / d_max), and the
// same statistic rejects samplers that miss a factor of the density.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "kiri/geometry/medium/fog_partition.hpp"
#include "kiri/geometry/particles/particles.hpp"

using namespace kiri::geometry;

namespace {

constexpr int bins = 10;
// Pearson's chi-square with 9 degrees of freedom exceeds 27.9 with probability 0.001.
constexpr double chi_square_bound = 27.9;
using Histogram = std::array<double, bins>;

// A shell on a slope (bottom 100 + 0.2 x + 0.1 y), thickening along x (T = 50 + 0.15 x, 50 to
// 200 m), its coverage rising along y (0.3 to 1): every grid linear, so its bilinear
// interpolation is exact and the density has a closed form,
//   d = c(y) (1 - 0.9 h) [detail, dissipation],  dz = T(x) dh.
constexpr double side = 1000.0;
double bottom_at(double x, double y) { return 100.0 + 0.2 * x + 0.1 * y; }
double thickness_at(double x) { return 50.0 + 0.15 * x; }
double coverage_at(double y) { return 0.3 + 0.7 * y / side; }

Medium sloped_shell(bool noisy = false)
{
    MediumGrid g;
    g.nx = g.ny = 11;
    g.dx = g.dy = side / 10.0;
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            const double x = i * g.dx, y = j * g.dy;
            g.bottom.push_back(bottom_at(x, y));
            g.floor.push_back(bottom_at(x, y));
            g.top.push_back(bottom_at(x, y) + thickness_at(x));
            g.coverage.push_back(coverage_at(y));
        }
    MediumOptions o;
    o.top_density = 0.1;
    MediumDetail d;
    d.detail = 0.0;
    if (noisy) {
        d.detail = 0.6;
        d.detail_scale = 1000.0;  // features of 250 m and more
        d.time = 1800.0;
        d.dissipation_half_life = 1800.0;  // 0.5 at the bottom, 0.25 at the top
    }
    return Medium(std::move(g), o, d);
}

ParticleOptions one_candidate_each(int count, std::uint64_t seed = 5)
{
    ParticleOptions o;
    o.count = count;
    o.candidates = 1.0;
    o.seed = seed;
    return o;
}

struct Histograms {
    Histogram x{}, y{}, h{};
};

// Bins of x and y over the square, of h over [h0, 1].
Histograms histograms(const std::vector<glm::dvec3>& points, double h0)
{
    Histograms out;
    const auto bin = [](double t) { return std::clamp(int(t * bins), 0, bins - 1); };
    for (const glm::dvec3& p : points) {
        out.x[bin(p.x / side)] += 1.0;
        out.y[bin(p.y / side)] += 1.0;
        const double h = (p.z - bottom_at(p.x, p.y)) / thickness_at(p.x);
        out.h[bin((h - h0) / (1.0 - h0))] += 1.0;
    }
    return out;
}

// Expected counts of n points whose density along [a, b] is f, by the midpoint rule.
Histogram expected(const std::function<double(double)>& f, double a, double b, double n)
{
    Histogram e{};
    double total = 0.0;
    const int steps = 1000;
    for (int k = 0; k < bins; ++k)
        for (int s = 0; s < steps; ++s) {
            const double t = a + (b - a) * (k + (s + 0.5) / steps) / bins;
            e[k] += f(t);
        }
    for (double v : e)
        total += v;
    for (double& v : e)
        v *= n / total;
    return e;
}

double chi_square(const Histogram& observed, const Histogram& expected_counts)
{
    double sum = 0.0;
    for (int k = 0; k < bins; ++k)
        sum += (observed[k] - expected_counts[k]) * (observed[k] - expected_counts[k]) / expected_counts[k];
    return sum;
}

// Two samples of sizes n and m against each other (9 degrees of freedom as above).
double chi_square_two_samples(const Histogram& a, const Histogram& b)
{
    double n = 0.0, m = 0.0, sum = 0.0;
    for (int k = 0; k < bins; ++k) {
        n += a[k];
        m += b[k];
    }
    for (int k = 0; k < bins; ++k)
        if (a[k] + b[k] > 0.0) {
            const double d = std::sqrt(m / n) * a[k] - std::sqrt(n / m) * b[k];
            sum += d * d / (a[k] + b[k]);
        }
    return sum;
}

std::vector<glm::dvec3> positions(const ParticleCloud& c)
{
    std::vector<glm::dvec3> p;
    for (const Particle& q : c.particles)
        p.push_back(q.position);
    return p;
}

// The sampler as it was: uniform in the Medium's box, kept with probability q / d_max.
std::vector<glm::dvec3> box_rejection(const Medium& m, const HeightShare& share, std::size_t n, unsigned seed)
{
    std::mt19937_64 rng(seed);
    const auto u = [&] { return double(rng() >> 11) * 0x1.0p-53; };
    const Bounds3& box = m.bounds();
    const double d_max = m.max_extinction() / m.options().extinction;
    std::vector<glm::dvec3> out;
    while (out.size() < n) {
        const glm::dvec3 p = box.min + (box.max - box.min) * glm::dvec3(u(), u(), u());
        double q = m.density(p);
        if (share.share) {
            const double h = m.height_fraction(p);
            q *= h > share.from ? std::clamp(share.share(h), 0.0, share.max) : 0.0;
        }
        if (u() * d_max < q)
            out.push_back(p);
    }
    return out;
}

}  // namespace

TEST(ParticleDistribution, TheTopBandFollowsItsDensity)
{
    // Combined rendering's default share: the top 35 % of the shell, rising to 0.5 at the top.
    const Medium m = sloped_shell();
    const FogPartition partition;
    const HeightShare share = particle_height_share(partition);
    const double h0 = 1.0 - partition.particle_band;
    const int n = 20000;
    const ParticleCloud c = sample_particles(m, one_candidate_each(n), "", share);
    ASSERT_EQ(c.particles.size(), std::size_t(n));
    const Histograms got = histograms(positions(c), h0);

    const auto along_h = [&](double h) { return (1.0 - 0.9 * h) * particle_share(partition, h, 1e30); };
    const Histogram ex = expected(thickness_at, 0.0, side, n), ey = expected(coverage_at, 0.0, side, n),
                    eh = expected(along_h, h0, 1.0, n);
    EXPECT_LT(chi_square(got.x, ex), chi_square_bound);
    EXPECT_LT(chi_square(got.y, ey), chi_square_bound);
    EXPECT_LT(chi_square(got.h, eh), chi_square_bound);

    // The density integral: int c dy int T dx int (1 - 0.9 h) share(h) dh, by the midpoint rule.
    double along_h_integral = 0.0;
    for (int s = 0; s < 100000; ++s)
        along_h_integral += along_h((s + 0.5) / 100000.0) / 100000.0;
    const double integral = (0.65 * side) * (50.0 + 0.075 * side) * side * along_h_integral;
    EXPECT_NEAR(c.density_integral, integral, 0.02 * integral);

    // The statistic has the power to tell: points uniform in the band (no density, no share)
    // and points drawn by density alone in (x, y, h) (missing dz = T dh) fail it.
    std::mt19937_64 rng(9);
    const auto u = [&] { return double(rng() >> 11) * 0x1.0p-53; };
    std::vector<glm::dvec3> uniform_band, without_thickness;
    while (without_thickness.size() < std::size_t(n)) {
        const double x = side * u(), y = side * u(), h = h0 + (1.0 - h0) * u();
        const glm::dvec3 p(x, y, bottom_at(x, y) + h * thickness_at(x));
        if (uniform_band.size() < std::size_t(n))
            uniform_band.push_back(p);
        if (u() < coverage_at(y) * along_h(h) / 0.5)
            without_thickness.push_back(p);
    }
    const Histograms flat = histograms(uniform_band, h0), thin = histograms(without_thickness, h0);
    EXPECT_GT(chi_square(flat.x, expected(thickness_at, 0.0, side, n)), 10.0 * chi_square_bound);
    EXPECT_GT(chi_square(flat.h, eh), 10.0 * chi_square_bound);
    EXPECT_GT(chi_square(thin.x, ex), 10.0 * chi_square_bound);
    EXPECT_LT(chi_square(thin.h, eh), chi_square_bound);  // its h is right

    // A fraction of the trials the whole box needed: the box's acceptance is integral / (box d_max).
    const Bounds3& box = m.bounds();
    const double box_trials = double(n) * (box.max - box.min).x * (box.max - box.min).y * (box.max - box.min).z *
        (m.max_extinction() / m.options().extinction) / integral;
    EXPECT_LT(double(c.trial_count), 0.1 * box_trials) << c.trial_count << " trials, the box " << box_trials;
}

TEST(ParticleDistribution, TheWholeShellFollowsItsDensity)
{
    const Medium m = sloped_shell();
    const int n = 20000;
    const ParticleCloud c = sample_particles(m, one_candidate_each(n));
    ASSERT_EQ(c.particles.size(), std::size_t(n));
    const Histograms got = histograms(positions(c), 0.0);
    EXPECT_LT(chi_square(got.x, expected(thickness_at, 0.0, side, n)), chi_square_bound);
    EXPECT_LT(chi_square(got.y, expected(coverage_at, 0.0, side, n)), chi_square_bound);
    EXPECT_LT(chi_square(got.h, expected([](double h) { return 1.0 - 0.9 * h; }, 0.0, 1.0, n)), chi_square_bound);
    const double integral = (0.65 * side) * (50.0 + 0.075 * side) * side * 0.55;
    EXPECT_NEAR(c.density_integral, integral, 0.02 * integral);
}

TEST(ParticleDistribution, NoiseAndDissipationAsTheBoxSamplerDrawsThem)
{
    // With the drifting noise and the dissipation the density has no closed form: the sampler
    // as it was (uniform in the box) is the oracle, two samples against each other.
    const Medium m = sloped_shell(true);
    for (const HeightShare& share : {HeightShare{}, particle_height_share(FogPartition{})}) {
        const double h0 = share.share ? share.from : 0.0;
        const int n = 10000;
        const ParticleCloud c = sample_particles(m, one_candidate_each(n, 7), "", share);
        ASSERT_EQ(c.particles.size(), std::size_t(n));
        const Histograms got = histograms(positions(c), h0);
        const Histograms oracle = histograms(box_rejection(m, share, n, 11), h0);
        EXPECT_LT(chi_square_two_samples(got.x, oracle.x), chi_square_bound);
        EXPECT_LT(chi_square_two_samples(got.y, oracle.y), chi_square_bound);
        EXPECT_LT(chi_square_two_samples(got.h, oracle.h), chi_square_bound);
        // The noise and the dissipation move the histograms: the oracle tells them apart from
        // the same shell without either.
        if (share.share)
            continue;
        const Histograms smooth =
            histograms(positions(sample_particles(sloped_shell(), one_candidate_each(n, 7), "", share)), h0);
        EXPECT_GT(chi_square_two_samples(smooth.x, oracle.x) + chi_square_two_samples(smooth.y, oracle.y) +
                      chi_square_two_samples(smooth.h, oracle.h),
                  3.0 * chi_square_bound);
    }
}
