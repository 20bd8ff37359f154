// Sampling particles in a Medium (particles.hpp): deterministic, inside the fog and above its
// floor (the fog's rectangle given), density-weighted, blue noise, carrying the Medium's
// extinction; options and PLY export.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <cstring>
#include <random>

#include <glm/geometric.hpp>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/medium/fog_partition.hpp"
#include "kiri/geometry/particles/particle_footprint.hpp"
#include "kiri/geometry/particles/particles.hpp"
#include "kiri/geometry/scene/scene.hpp"
#include "particle_test_clouds.hpp"
#include "temp_path.hpp"

using namespace kiri::geometry;
using kiri::test::slab_medium;

namespace {

ParticleOptions options(int count, std::uint64_t seed = 3)
{
    ParticleOptions o;
    o.count = count;
    o.seed = seed;
    return o;
}

// Smallest distance to another particle, in units of the particle's local spacing, averaged.
double mean_nearest(const ParticleCloud& c)
{
    double sum = 0.0;
    for (std::size_t i = 0; i < c.particles.size(); ++i) {
        double best = 1e300;
        for (std::size_t j = 0; j < c.particles.size(); ++j)
            if (j != i)
                best = std::min(best, glm::distance(c.particles[i].position, c.particles[j].position));
        sum += best;
    }
    return sum / double(c.particles.size());
}

}  // namespace

TEST(ParticleSampling, DeterministicForASeed)
{
    const Medium m = slab_medium();
    const ParticleCloud a = sample_particles(m, options(500, 11)), b = sample_particles(m, options(500, 11));
    const ParticleCloud c = sample_particles(m, options(500, 12));
    ASSERT_EQ(a.particles.size(), 500u);
    ASSERT_EQ(b.particles.size(), 500u);
    bool differs = false;
    for (std::size_t i = 0; i < 500; ++i) {
        EXPECT_EQ(a.particles[i].position, b.particles[i].position);
        EXPECT_EQ(a.particles[i].radius, b.particles[i].radius);
        EXPECT_EQ(a.particles[i].optical_depth, b.particles[i].optical_depth);
        differs = differs || a.particles[i].position != c.particles[i].position;
    }
    EXPECT_TRUE(differs);
}

TEST(ParticleSampling, InsideTheFogAboveItsFloor)
{
    // Ground at 180 m cuts the shell (100..300): nothing below 180.
    MediumGrid g;
    g.nx = g.ny = 2;
    g.x0 = g.y0 = 0.0;
    g.dx = g.dy = 500.0;
    g.bottom.assign(4, 100.0);
    g.top.assign(4, 300.0);
    g.floor.assign(4, 180.0);
    g.coverage.assign(4, 1.0);
    MediumDetail d;
    d.detail = 0.0;
    const Medium m(g, MediumOptions{}, d);
    const ParticleCloud c = sample_particles(m, options(800));
    for (const Particle& p : c.particles) {
        EXPECT_GE(p.position.z, 180.0);
        EXPECT_LE(p.position.z, 300.0);
        EXPECT_GT(m.density(p.position), 0.0);
    }
    // The fog's rectangle, where the renderers clip every footprint: the grid's, 0..500 m.
    EXPECT_EQ(c.fog_xy_min, glm::dvec2(0.0, 0.0));
    EXPECT_EQ(c.fog_xy_max, glm::dvec2(500.0, 500.0));
    EXPECT_EQ(ParticleCloud{}.fog_xy_min.x, -std::numeric_limits<double>::infinity());
}

TEST(ParticleSampling, DensityWeighted)
{
    // The layers' profile: density 1 at the bottom, 0.1 at the top, linear. Expected share of the
    // lower half: int_0^0.5 (1 - 0.9 h) dh / int_0^1 (1 - 0.9 h) dh = 0.3875 / 0.55.
    const Medium m = slab_medium(1000.0, 100.0, 300.0);
    const ParticleCloud c = sample_particles(m, options(4000));
    double lower = 0.0;
    for (const Particle& p : c.particles)
        lower += p.position.z < 200.0 ? 1.0 : 0.0;
    EXPECT_NEAR(lower / 4000.0, 0.3875 / 0.55, 0.02);
    // Sparser particles are larger: radius follows the local spacing d^(-1/3).
    double r_low = 0.0, r_high = 0.0;
    int n_low = 0, n_high = 0;
    for (const Particle& p : c.particles) {
        if (p.position.z < 130.0) {
            r_low += p.radius;
            ++n_low;
        } else if (p.position.z > 270.0) {
            r_high += p.radius;
            ++n_high;
        }
    }
    EXPECT_GT(r_high / n_high, 1.5 * r_low / n_low);
}

TEST(ParticleSampling, BlueNoise)
{
    // Uniform shell: sample elimination spreads the particles; independent random points of the
    // same density have a mean nearest-neighbour distance of ~0.554 spacing (Poisson, 3D).
    const Medium m = slab_medium(1000.0, 0.0, 400.0, true);
    const ParticleCloud c = sample_particles(m, options(1500));
    const double spacing = c.spacing;
    EXPECT_NEAR(spacing, std::cbrt(1000.0 * 1000.0 * 400.0 / 1500.0), 0.02 * spacing);
    EXPECT_GT(mean_nearest(c) / spacing, 0.75);
    // The same number of plain random points (1 candidate each: nothing eliminated).
    ParticleOptions plain = options(1500);
    plain.candidates = 1.0;
    plain.relax = 0;
    EXPECT_LT(mean_nearest(sample_particles(m, plain)) / spacing, 0.62);
}

// A blanket one particle deep (40 m of fog, particles ~100 m apart across it), seen from above:
// its column's optical depth, the particles' footprints summed, at points of the inner square.
// Blue noise still crowds and thins out; the relaxation's sweeps even it out towards a
// lattice's (the spread of the columns 0.32 -> 0.21 in 15 sweeps, 0.18 in 30), and keep the
// density where it was (as many particles in each half as before).
TEST(ParticleSampling, RelaxedParticlesEvenOutTheBlanketsColumns)
{
    const Medium m = slab_medium(2000.0, 100.0, 140.0, true);
    const auto column_spread = [&](const ParticleCloud& c, double& west_share) {
        std::vector<double> tau;
        for (int j = 0; j < 40; ++j)
            for (int i = 0; i < 40; ++i) {
                const glm::dvec2 q(-600.0 + 1200.0 * (i + 0.5) / 40.0, -600.0 + 1200.0 * (j + 0.5) / 40.0);
                double sum = 0.0;
                for (const Particle& p : c.particles)
                    sum += p.optical_depth * footprint_profile(glm::distance(glm::dvec2(p.position), q) / p.radius);
                tau.push_back(sum);
            }
        double mean = 0.0, var = 0.0;
        for (double t : tau)
            mean += t / double(tau.size());
        for (double t : tau)
            var += (t - mean) * (t - mean) / double(tau.size());
        west_share = 0.0;
        for (const Particle& p : c.particles)
            west_share += p.position.x < 0.0 ? 1.0 / double(c.particles.size()) : 0.0;
        return std::sqrt(var) / mean;
    };
    ParticleOptions eliminated = options(400, 5);
    eliminated.relax = 0;
    const ParticleCloud before = sample_particles(m, eliminated), after = sample_particles(m, options(400, 5));
    ASSERT_EQ(after.particles.size(), 400u);
    double west_before = 0.0, west_after = 0.0;
    const double spread_before = column_spread(before, west_before), spread_after = column_spread(after, west_after);
    EXPECT_LT(spread_after, 0.7 * spread_before) << spread_before << " -> " << spread_after;
    EXPECT_NEAR(west_after, west_before, 0.03);
    for (const Particle& p : after.particles) {  // inside the fog, each as high as it was drawn
        EXPECT_GT(m.density(p.position), 0.0);
        EXPECT_GE(p.position.z, 100.0);
        EXPECT_LE(p.position.z, 140.0);
    }
}

TEST(ParticleSampling, CarriesTheMediumsExtinction)
{
    const Medium m = slab_medium(1000.0, 100.0, 300.0, false, 0.03);
    const ParticleCloud c = sample_particles(m, options(3000));
    // Density integral of the slab: area * thickness * mean profile 0.55.
    EXPECT_NEAR(c.density_integral, 1000.0 * 1000.0 * 200.0 * 0.55, 0.01 * 1.1e8);
    double carried = 0.0;
    for (const Particle& p : c.particles) {
        carried += p.optical_depth * footprint_area() * p.radius * p.radius;
        EXPECT_EQ(p.albedo, m.options().albedo);
    }
    EXPECT_NEAR(carried, 0.03 * c.density_integral, 1e-9 * carried);
    // By default no light stays in the sun's beam: the shared lighting model carries it.
    EXPECT_EQ(c.forward_scattering, 0.0);
    ParticleOptions harris = options(300);
    harris.forward_scattering = forward_scattering_fraction(m.options().anisotropy);  // Harris's own model
    EXPECT_NEAR(sample_particles(m, harris).forward_scattering, 0.228, 1e-3);
    // Overrides.
    ParticleOptions o = options(300);
    o.extinction = 0.06;
    o.albedo = 0.5;
    o.forward_scattering = 0.1;
    o.radius_min = 7.0;
    o.radius_max = 9.0;
    const ParticleCloud d = sample_particles(m, o);
    carried = 0.0;
    for (const Particle& p : d.particles) {
        carried += p.optical_depth * footprint_area() * p.radius * p.radius;
        EXPECT_EQ(p.albedo, 0.5);
        EXPECT_GE(p.radius, 7.0);
        EXPECT_LE(p.radius, 9.0);
    }
    EXPECT_NEAR(carried, 0.06 * d.density_integral, 1e-9 * carried);
    EXPECT_EQ(d.forward_scattering, 0.1);
}

TEST(ParticleSampling, SpacingGivesTheCount)
{
    const Medium m = slab_medium(1000.0, 0.0, 200.0, true);
    ParticleOptions o;
    o.spacing = 40.0;  // 2e8 m^3 / 40^3 = 3125
    const ParticleCloud c = sample_particles(m, o);
    EXPECT_NEAR(double(c.particles.size()), 3125.0, 60.0);
}

TEST(ParticleSampling, BadOptionsNameTheirKey)
{
    const Medium m = slab_medium();
    const auto message = [&](ParticleOptions o) {
        try {
            sample_particles(m, o, "s.json");
        } catch (const kiri::InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    ParticleOptions o;
    o.count = 0;
    EXPECT_EQ(message(o), "s.json: /particles/count: must be in [1, 2000000], got 0");
    o = {};
    o.resolution = 600;
    EXPECT_EQ(message(o), "s.json: /particles/resolution: must be in [16, 512], got 600");
    o = {};
    o.count = 1000000;
    o.candidates = 30.0;
    EXPECT_EQ(message(o), "s.json: /particles/candidates: count * candidates is above the limit of 2e7 points");
}

TEST(ParticleSampling, SceneSection)
{
    const auto parse = [](const std::string& particles) {
        return parse_scene(
            R"({"terrain": {"path": "t.tif"}, "sun": {"direction": [0, 0, 1]}, "particles": )" + particles + "}",
            "s.json", "/");
    };
    const Scene s = parse(R"({"count": 900, "radius": [5, 20], "albedo": 0.7, "format": "r32f", "frame": "light",
                              "resolution": 256, "seed": 5})");
    EXPECT_EQ(s.particles.count, 900);
    EXPECT_EQ(s.particles.radius_min, 5.0);
    EXPECT_EQ(s.particles.radius_max, 20.0);
    EXPECT_EQ(s.particles.albedo, 0.7);
    EXPECT_FALSE(s.particles.half_float);
    EXPECT_EQ(s.particles.frame, LightFrame::light);
    EXPECT_EQ(s.particles.resolution, 256);
    EXPECT_EQ(scene_to_json(parse_scene(scene_to_json(s), "again.json", "/")), scene_to_json(s));
    const auto error = [&](const std::string& particles) {
        try {
            parse(particles);
        } catch (const kiri::InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_EQ(error(R"({"cuont": 3})").rfind("s.json: /particles/cuont: unknown key (expected one of: albedo, ", 0),
              0u);
    EXPECT_EQ(error(R"({"count": 3, "spacing": 4})"),
              "s.json: /particles: give count or spacing, not both (each sets the number of particles)");
    EXPECT_EQ(error(R"({"radius": [5, 2]})"), "s.json: /particles/radius: the minimum is above the maximum");
    EXPECT_EQ(error(R"({"radius": 5})"), "s.json: /particles/radius: expected an array of 2 numbers [min, max] (m)");
    EXPECT_EQ(error(R"({"format": "rgba8"})"),
              "s.json: /particles/format: expected \"r16f\" or \"r32f\", got \"rgba8\"");
    EXPECT_EQ(error(R"({"resolution": 8})"), "s.json: /particles/resolution: must be in [16, 512], got 8");
    EXPECT_EQ(error(R"({"albedo": 2})"), "s.json: /particles/albedo: must be in [0, 1], got 2");
}

TEST(ParticleSampling, PlyExport)
{
    ParticleCloud c = sample_particles(slab_medium(), options(50));
    c.particles[1].above_ground = 0.625;  // as set_above_ground leaves them
    c.particles[1].floor = 412.5;
    c.particles[1].floor_slope = {0.125, -0.25};
    c.particles[1].top = 480.25;
    c.particles[1].top_slope = {-0.5, 0.0625};
    const std::filesystem::path path = kiri::test::temp_path("particles_test.ply");
    write_particles_ply(path.string(), c);
    std::ifstream in(path, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t end = text.find("end_header\n");
    ASSERT_NE(end, std::string::npos);
    EXPECT_NE(text.find("element vertex 50\n"), std::string::npos);
    EXPECT_NE(text.find("property float optical_depth\n"), std::string::npos);
    EXPECT_NE(text.find("property float above_ground\nproperty float floor\nproperty float floor_dzdx\n"
                        "property float floor_dzdy\nproperty float top\nproperty float top_dzdx\n"
                        "property float top_dzdy\n"),
              std::string::npos);
    ASSERT_EQ(text.size(), end + 11 + 50 * 13 * sizeof(float));
    float v[13];
    std::memcpy(v, text.data() + end + 11 + 13 * sizeof(float), sizeof v);  // the second particle
    EXPECT_EQ(v[0], float(c.particles[1].position.x));
    EXPECT_EQ(v[2], float(c.particles[1].position.z));
    EXPECT_EQ(v[3], float(c.particles[1].radius));
    EXPECT_EQ(v[4], float(c.particles[1].optical_depth));
    EXPECT_EQ(v[6], 0.625f);
    EXPECT_EQ(v[7], 412.5f);
    EXPECT_EQ(v[8], 0.125f);
    EXPECT_EQ(v[9], -0.25f);
    EXPECT_EQ(v[10], 480.25f);
    EXPECT_EQ(v[11], -0.5f);
    EXPECT_EQ(v[12], 0.0625f);
    float first[13];  // no floor under the first: the lowest float, finite; no top: the largest
    std::memcpy(first, text.data() + end + 11, sizeof first);
    EXPECT_EQ(first[6], 1.0f);
    EXPECT_EQ(first[7], std::numeric_limits<float>::lowest());
    EXPECT_EQ(first[10], std::numeric_limits<float>::max());
    EXPECT_FALSE(std::filesystem::exists(path.string() + ".tmp"));
    std::filesystem::remove(path);
    EXPECT_THROW(write_particles_ply("/nonexistent/dir/p.ply", c), kiri::IoError);
}

TEST(ParticleSampling, AWeightSamplesAShareOfTheMedium)
{
    // Combined rendering gives the particles the top band: weight = the quintic step of h over
    // [0.5, 1]. The slab's profile is 1 - 0.9 h over 200 m, so the weighted integral is
    // area * 200 * int_0^1 (1 - 0.9 h) s(h) dh with s the step from 0.5 to 1.
    const Medium m = slab_medium(1000.0, 100.0, 300.0, false, 0.03);
    FogPartition partition;
    partition.particle_share = 1.0;
    partition.particle_band = 0.5;
    partition.particle_depth = 0.0;  // every thickness (below: the depth)
    const ParticleCloud c = sample_particles(m, options(3000), "", particle_height_share(partition));
    EXPECT_EQ(c.share_radius, 0.0);
    double expected = 0.0;
    const int n = 100000;
    for (int i = 0; i < n; ++i) {  // midpoint rule
        const double h = (i + 0.5) / n;
        expected += (1.0 - 0.9 * h) * smoother_step(0.5, 1.0, h) / n;
    }
    expected *= 1000.0 * 1000.0 * 200.0;
    EXPECT_NEAR(c.density_integral, expected, 0.02 * expected);
    for (const Particle& p : c.particles)
        EXPECT_GT(p.position.z, 200.0 - 1e-9);  // none below the band (h = 0.5)
    double carried = 0.0;
    for (const Particle& p : c.particles)
        carried += p.optical_depth * footprint_area() * p.radius * p.radius;
    EXPECT_NEAR(carried, 0.03 * c.density_integral, 1e-9 * carried);
}

TEST(ParticleSampling, TheShareKeepsToFogThickForTheParticles)
{
    // A fog 400 m thick for x < -125 m, 40 m for x > 125 m (linear between): with the depth rule
    // the band's particles lie only where the fog is thick for them. The radius the depth counts
    // in is the particles' at full density without the rule, radius_scale cbrt(integral / count),
    // the integral of d share(h) over the Medium by the midpoint rule here.
    MediumGrid g;
    g.nx = 9;
    g.ny = 3;
    g.x0 = g.y0 = -500.0;
    g.dx = 125.0;
    g.dy = 500.0;
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            const double x = g.x0 + i * g.dx;
            g.bottom.push_back(100.0);
            g.floor.push_back(100.0);
            g.top.push_back(x < -100.0 ? 500.0 : x > 100.0 ? 140.0 : 320.0);
            g.coverage.push_back(1.0);
        }
    MediumOptions o;
    o.extinction = 0.02;
    MediumDetail d;
    d.detail = 0.0;
    const Medium m(std::move(g), o, d);
    FogPartition partition;
    partition.particle_share = 1.0;
    partition.particle_band = 0.5;
    partition.particle_depth = 12.0;
    const int count = 3000;
    const ParticleCloud c = sample_particles(m, options(count), "", particle_height_share(partition));
    ASSERT_GT(c.particles.size(), 1000u);

    const int n = 200;
    const auto integral = [&](const FogPartition* depth) {
        double sum = 0.0;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j)
                for (int k = 0; k < n; ++k) {
                    const glm::dvec3 p(-500.0 + 1000.0 * (i + 0.5) / n, -500.0 + 1000.0 * (j + 0.5) / n,
                                       100.0 + 400.0 * (k + 0.5) / n);
                    const double h = m.height_fraction(p);
                    const MediumColumn col = m.column(p.x, p.y);
                    sum += m.density(p) * smoother_step(0.5, 1.0, h) *
                        (depth ? particle_depth_share(*depth, col.top - col.floor) : 1.0);
                }
        return sum * 1000.0 * 1000.0 * 400.0 / (double(n) * n * n);
    };
    const double r0 = 1.5 * std::cbrt(integral(nullptr) / count);
    EXPECT_NEAR(c.share_radius, r0, 0.02 * r0);
    // Thick (400 m) is over 12 radii, thin (40 m) under 4: the rule cuts between.
    ASSERT_GT(400.0, 12.0 * c.share_radius);
    ASSERT_LT(40.0, 4.0 * c.share_radius);
    FogPartition rule = partition;
    rule.particle_radius = c.share_radius;
    EXPECT_NEAR(c.density_integral, integral(&rule), 0.03 * integral(&rule));
    for (const Particle& p : c.particles) {
        const MediumColumn col = m.column(p.position.x, p.position.y);
        EXPECT_GT(particle_depth_share(rule, col.top - col.floor), 0.0) << p.position.x;
    }
}

TEST(ParticleSampling, AThinFogGetsFewParticlesNotAnError)
{
    // A weight that leaves a sliver of the slab (the top 1e-4 of its height, as the top band of a
    // thin fog does): far fewer candidates than count * candidates can be found in reasonable
    // time, so the particles are fewer, in proportion, and still carry the share's extinction.
    const Medium m = slab_medium(1000.0, 100.0, 300.0, false, 0.03);
    const HeightShare sliver{[](double h) { return h > 1.0 - 1e-4 ? 1.0 : 0.0; }};
    const ParticleCloud c = sample_particles(m, options(20000), "", sliver);
    EXPECT_LT(c.particles.size(), 20000u);
    EXPECT_GT(c.candidate_count, 0u);
    EXPECT_EQ(c.particles.size(), std::max<std::size_t>(1, std::size_t(double(c.candidate_count) / 5.0)));
    double carried = 0.0;
    for (const Particle& p : c.particles) {
        EXPECT_GT(p.position.z, 300.0 - 200.0 * 1e-4 - 1e-9);
        EXPECT_TRUE(std::isfinite(p.optical_depth));
        carried += p.optical_depth * footprint_area() * p.radius * p.radius;
    }
    if (!c.particles.empty()) {
        EXPECT_NEAR(carried, 0.03 * c.density_integral, 1e-9 * carried);
    }
    // No fog at all under the weight: no particles, and no error.
    const ParticleCloud none = sample_particles(m, options(2000), "", {[](double) { return 0.0; }});
    EXPECT_TRUE(none.particles.empty());
    EXPECT_EQ(none.candidate_count, 0u);
}
