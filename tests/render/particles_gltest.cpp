// The particle passes on the GPU (attenuation.hpp, Renderer::set_particles): the attenuation
// buffer against its CPU twin and the exact Harris pass, order independence, opaque particles,
// lights along an axis and a diagonal, rebuilds only on change, Harris's GL light pass, and the
// billboards' self-shadowing. Small clouds: llvmpipe on two cores.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <glm/geometric.hpp>

#include "geometry/particle_test_clouds.hpp"
#include "kiri/geometry/particles/attenuation_cpu.hpp"
#include "kiri/geometry/particles/harris_reference.hpp"
#include "kiri/render/attenuation.hpp"
#include "kiri/render/renderer.hpp"
#include "render/render_fixture.hpp"

namespace {

namespace g = kiri::geometry;
using kiri::render::AttenuationBuffer;
using kiri::render::AttenuationOptions;

class ParticlesGl : public kiri::test::GlTest {};

AttenuationOptions options(int resolution, bool half = false)
{
    AttenuationOptions o;
    o.resolution = resolution;
    o.half_float = half;
    return o;
}

double mean_relative_error(const std::vector<float>& gamma, const std::vector<double>& exact)
{
    double sum = 0.0;
    for (std::size_t k = 0; k < exact.size(); ++k)
        sum += std::abs(gamma[k] - exact[k]) / exact[k];
    return sum / double(exact.size());
}

}  // namespace

TEST_F(ParticlesGl, BufferEqualsItsCpuTwin)
{
    const g::ParticleCloud c = kiri::test::ball_cloud(400, 150.0, 30.0, 0.5);
    const glm::dvec3 light(0.3, -0.5, 0.8);
    AttenuationBuffer b;
    b.set_particles(c);
    ASSERT_TRUE(b.update(light, options(32)));
    const g::AttenuationVolume cpu = g::build_attenuation_cpu(c, b.grid());
    const std::vector<float> gpu = b.read_log_gamma();
    ASSERT_EQ(gpu.size(), cpu.log_gamma.size());
    // Each deposit is rounded to 1 / scale; a column sums at most a few hundred.
    const double tolerance = 400.0 / b.fixed_point_scale() + 1e-5;
    double worst = 0.0;
    for (std::size_t i = 0; i < gpu.size(); ++i)
        worst = std::max(worst, double(std::abs(gpu[i] - cpu.log_gamma[i])));
    EXPECT_LT(worst, tolerance);
    // A particle's light sums a few dozen rounded deposits.
    const std::vector<float> gamma = b.gamma_at_particles();
    for (std::size_t k = 0; k < c.particles.size(); ++k)
        ASSERT_NEAR(gamma[k], g::particle_gamma(cpu, c, k), 30.0 / b.fixed_point_scale() + 1e-5) << k;
    // Half floats: log Gamma to 11 bits.
    ASSERT_TRUE(b.update(light, options(32, true)));
    const std::vector<float> half = b.read_log_gamma();
    for (std::size_t i = 0; i < half.size(); ++i)
        ASSERT_NEAR(half[i], cpu.log_gamma[i], 1e-3 * std::abs(cpu.log_gamma[i]) + tolerance) << i;
    EXPECT_EQ(b.texture_bytes(), 32u * 32u * 32u * 2u);
}

TEST_F(ParticlesGl, BallsCutAtTheFogsFloorAndTopDepositAsTheCpuTwinDoes)
{
    // Every ball knows a tilted top's plane and some a floor's, both through the cloud: the
    // deposit cuts each column at them and gives the cut mass back (seen_gain), in both the
    // packed layout (thin particles) and the 32-bit one, and each particle's read takes its own
    // cut cylinder out (particle_gamma).
    const glm::dvec3 light(0.3, -0.5, 0.8);
    for (const double tau : {0.05, 0.5}) {
        g::ParticleCloud c = kiri::test::ball_cloud(1500, 200.0, 35.0, tau);
        for (std::size_t k = 0; k < c.particles.size(); ++k) {
            g::Particle& p = c.particles[k];
            p.top_slope = glm::dvec2(0.15, -0.1);
            p.top = 1060.0 + glm::dot(p.top_slope, glm::dvec2(p.position));
            p.above_ground = k % 2 ? 1.0 : 0.6;  // the share drawn, its cut given back
            if (k % 3 == 0) {
                p.floor_slope = glm::dvec2(-0.1, 0.2);
                p.floor = 900.0 + glm::dot(p.floor_slope, glm::dvec2(p.position));
            }
        }
        AttenuationBuffer b;
        b.set_particles(c);
        ASSERT_TRUE(b.update(light, options(48)));
        EXPECT_EQ(b.packed_deposit(), tau < 0.1);
        const g::AttenuationVolume cpu = g::build_attenuation_cpu(c, b.grid());
        const std::vector<float> gpu = b.read_log_gamma();
        ASSERT_EQ(gpu.size(), cpu.log_gamma.size());
        double worst = 0.0;
        for (std::size_t i = 0; i < gpu.size(); ++i)
            worst = std::max(worst, double(std::abs(gpu[i] - cpu.log_gamma[i])));
        EXPECT_LT(worst, 400.0 / b.fixed_point_scale() + 1e-4) << tau;
        const std::vector<float> gamma = b.gamma_at_particles();
        for (std::size_t k = 0; k < c.particles.size(); ++k)
            ASSERT_NEAR(gamma[k], g::particle_gamma(cpu, c, k), 30.0 / b.fixed_point_scale() + 1e-4) << tau << " " << k;
        // The planes matter: the same balls uncut give another buffer.
        g::ParticleCloud uncut = c;
        for (g::Particle& p : uncut.particles) {
            p.top = HUGE_VAL;
            p.floor = -HUGE_VAL;
        }
        const g::AttenuationVolume plain = g::build_attenuation_cpu(uncut, b.grid());
        double moved = 0.0;
        for (std::size_t i = 0; i < gpu.size(); ++i)
            moved = std::max(moved, double(std::abs(plain.log_gamma[i] - cpu.log_gamma[i])));
        EXPECT_GT(moved, 100.0 * worst + 0.01) << tau;
    }
}

TEST_F(ParticlesGl, PackedDepositEqualsTheCpuTwinAndTheOrderDoesNotMatter)
{
    // Many thin particles: the deposit packs two columns to a word.
    g::ParticleCloud c = kiri::test::ball_cloud(3000, 300.0, 40.0, 0.05);
    const glm::dvec3 light(0.3, -0.5, 0.8);
    AttenuationBuffer b;
    b.set_particles(c);
    b.update(light, options(48));
    ASSERT_TRUE(b.packed_deposit());
    EXPECT_GE(b.fixed_point_scale(), 8192.0);
    const g::AttenuationVolume cpu = g::build_attenuation_cpu(c, b.grid());
    const std::vector<float> gpu = b.read_log_gamma();
    double worst = 0.0;
    for (std::size_t i = 0; i < gpu.size(); ++i)
        worst = std::max(worst, double(std::abs(gpu[i] - cpu.log_gamma[i])));
    EXPECT_LT(worst, 400.0 / b.fixed_point_scale() + 1e-5);
    const std::vector<float> gamma = b.gamma_at_particles();
    for (std::size_t k = 0; k < c.particles.size(); ++k)
        ASSERT_NEAR(gamma[k], g::particle_gamma(cpu, c, k), 30.0 / b.fixed_point_scale() + 1e-5) << k;
    std::mt19937 rng(5);
    std::shuffle(c.particles.begin(), c.particles.end(), rng);
    b.set_particles(c);
    ASSERT_TRUE(b.update(light, options(48)));
    EXPECT_EQ(b.read_log_gamma(), gpu);
}

TEST_F(ParticlesGl, BufferAgreesWithTheExactHarrisPass)
{
    const g::ParticleCloud c = kiri::test::ball_cloud(1500, 300.0, 45.0, 0.25);
    const glm::dvec3 light = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
    const std::vector<double> exact = g::harris_light_pass(c, light);
    AttenuationBuffer b;
    b.set_particles(c);
    b.update(light, options(64, true));
    const double e = mean_relative_error(b.gamma_at_particles(), exact);
    // The error is about a third of a voxel's optical depth along the light (docs/particles.md):
    // here ~0.06 per voxel at 64^3.
    EXPECT_LT(e, 0.03) << e;
}

TEST_F(ParticlesGl, OneParticleAndTwoOnALineToTheSun)
{
    const glm::dvec3 light = glm::dvec3(1.0, 2.0, 2.0) / 3.0;
    g::ParticleCloud c;
    c.forward_scattering = 0.2;
    c.particles = {{{10.0, 0.0, 100.0}, 8.0, 1.5, 0.9}};
    AttenuationBuffer b;
    b.set_particles(c);
    b.update(light, options(32));
    EXPECT_NEAR(b.gamma_at_particles()[0], 1.0, 1e-5);
    c.particles.push_back({glm::dvec3(10.0, 0.0, 100.0) - 50.0 * light, 6.0, 0.7, 0.5});
    b.set_particles(c);
    ASSERT_TRUE(b.update(light, options(32)));
    const std::vector<double> exact = g::harris_light_pass(c, light);
    const std::vector<float> gamma = b.gamma_at_particles();
    EXPECT_NEAR(gamma[0], 1.0, 1e-5);
    EXPECT_NEAR(gamma[1], exact[1], 0.01 * exact[1]);
}

TEST_F(ParticlesGl, ShuffledParticlesGiveTheSameBufferBitForBit)
{
    g::ParticleCloud c = kiri::test::ball_cloud(600, 200.0, 30.0, 0.5);
    const glm::dvec3 light(0.1, 0.7, 0.4);
    AttenuationBuffer b;
    b.set_particles(c);
    b.update(light, options(40));
    const std::vector<float> a = b.read_log_gamma();
    std::mt19937 rng(3);
    std::shuffle(c.particles.begin(), c.particles.end(), rng);
    b.set_particles(c);
    ASSERT_TRUE(b.update(light, options(40)));
    EXPECT_EQ(b.read_log_gamma(), a);  // integer sums: exact in any order
}

TEST_F(ParticlesGl, OpaqueParticlesStayFinite)
{
    g::ParticleCloud c;
    const double inf = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 12; ++k)  // black and opaque, one above the other: 12 * -16, clamped at -80
        c.particles.push_back({{0.0, 0.0, 5.0 * k}, 4.0, inf, 0.0});
    c.particles.push_back({{1.0, 0.0, 70.0}, 4.0, inf, 1.0});  // white and opaque: G = a c
    AttenuationBuffer b;
    b.set_particles(c);
    b.update({0, 0, 1}, options(24));
    for (float x : b.read_log_gamma()) {
        ASSERT_TRUE(std::isfinite(x));
        ASSERT_GE(x, -80.0f);
    }
    for (float gamma : b.gamma_at_particles()) {
        EXPECT_TRUE(std::isfinite(gamma));
        EXPECT_GE(gamma, 0.0f);
        EXPECT_LE(gamma, 1.0f);
    }
}

TEST_F(ParticlesGl, LightAlongAnAxisAndADiagonal)
{
    const g::ParticleCloud c = kiri::test::ball_cloud(800, 200.0, 35.0, 0.3);
    AttenuationBuffer b;
    b.set_particles(c);
    for (const glm::dvec3& light :
         {glm::dvec3(0, 0, 1), glm::dvec3(1, 0, 0), glm::dvec3(0, -1, 0), glm::dvec3(1, 1, 1), glm::dvec3(-1, 1, -1)}) {
        b.update(light, options(48));
        const double e = mean_relative_error(b.gamma_at_particles(), g::harris_light_pass(c, light));
        EXPECT_LT(e, 0.04) << light.x << " " << light.y << " " << light.z;
    }
}

TEST_F(ParticlesGl, HarrisGlLightPassFollowsTheRecurrence)
{
    const g::ParticleCloud c = kiri::test::ball_cloud(300, 150.0, 30.0, 0.4);
    const glm::dvec3 light(0.2, 0.4, 0.9);
    kiri::render::HarrisGlStats stats;
    const std::vector<float> gamma = kiri::render::harris_light_pass_gl(c, light, 0, &stats);
    EXPECT_GT(stats.buffer_size, 0);
    EXPECT_LE(stats.pixel_m, 30.0 / 4.0 + 1e-9);
    // Harris reads the buffer at the pixel holding the centre: its error shrinks with the pixel.
    const std::vector<double> exact = g::harris_light_pass(c, light);
    const double coarse = mean_relative_error(gamma, exact);
    const double fine = mean_relative_error(kiri::render::harris_light_pass_gl(c, light, 1024), exact);
    EXPECT_LT(coarse, 0.08);
    EXPECT_LT(fine, 0.01);
    EXPECT_LT(fine, 0.5 * coarse);
}

TEST_F(ParticlesGl, RendererRebuildsOnlyOnChange)
{
    const kiri::geometry::Terrain hill = kiri::test::gaussian_hill();
    g::ParticleCloud c = kiri::test::ball_cloud(200, 150.0, 30.0, 0.5);
    for (auto& p : c.particles)
        p.position.z -= 600.0;  // over the hill
    kiri::render::Renderer r;
    r.set_terrain(hill);
    r.set_particles(c);
    kiri::render::Camera cam;
    cam.position = {0.0, -1500.0, 700.0};
    cam.target = {0.0, 0.0, 300.0};
    r.draw(cam, 64, 48);
    EXPECT_EQ(r.last_stats().attenuation_rebuilds, 1);
    EXPECT_EQ(r.last_stats().particles, 200);
    for (int frame = 0; frame < 3; ++frame) {  // a static scene: none, even when the eye moves
        cam.position.x += 10.0;
        r.draw(cam, 64, 48);
        EXPECT_EQ(r.last_stats().attenuation_rebuilds, 0);
    }
    const g::ParticleCloud copy = c;  // equal particles are no change
    r.set_particles(copy);
    r.draw(cam, 64, 48);
    EXPECT_EQ(r.last_stats().attenuation_rebuilds, 0);
    kiri::render::SunLight sun;
    sun.direction = {0.1, 0.2, 1.0};
    r.set_sun(sun);
    r.draw(cam, 64, 48);
    EXPECT_EQ(r.last_stats().attenuation_rebuilds, 1);
    c.particles[7].position.x += 1.0;  // moved particles
    r.set_particles(c);
    r.draw(cam, 64, 48);
    EXPECT_EQ(r.last_stats().attenuation_rebuilds, 1);
    kiri::render::ParticleStyle style;
    style.buffer.resolution = 48;  // another resolution
    r.set_particles(c, style);
    r.draw(cam, 64, 48);
    EXPECT_EQ(r.last_stats().attenuation_rebuilds, 1);
    r.draw(cam, 64, 48);
    EXPECT_EQ(r.last_stats().attenuation_rebuilds, 0);
    EXPECT_EQ(r.attenuation().rebuild_count(), 4);
}

TEST_F(ParticlesGl, BillboardsAreSelfShadowed)
{
    // A slab of particles seen from the side with the sun overhead and no sky light: the top rows
    // of the slab get the sun, the lower ones only what the particles above let through.
    const kiri::geometry::Terrain flat = kiri::test::gaussian_hill(33, 100.0, 0.0);
    g::ParticleCloud c;
    c.forward_scattering = 0.2;
    c.scattering_octaves = 1;  // single scattering: the buffer's shadow alone (the light scattered
                               // more than once grows with depth, fog_lighting.hpp)
    std::mt19937_64 rng(9);
    const auto u = [&] { return double(rng() >> 11) * 0x1.0p-53; };
    for (int k = 0; k < 1500; ++k)
        c.particles.push_back({{600.0 * u() - 300.0, 600.0 * u() - 300.0, 200.0 + 200.0 * u()}, 35.0, 0.25, 0.95});
    kiri::render::Renderer r;
    r.set_terrain(flat, 1.0, false);  // the bare tile: behind the slab the dark void, not the sunlit surround
    r.set_particles(c);
    kiri::render::SunLight sun;
    sun.direction = {0.0, 0.0, 1.0};
    sun.intensity = 4.0;
    sun.ambient = glm::dvec3(0.0);
    r.set_sun(sun);
    kiri::render::Camera cam;
    cam.position = {0.0, -1400.0, 300.0};
    cam.target = {0.0, 0.0, 300.0};
    cam.fov_y_deg = 40.0;
    const int w = 96, h = 96;
    const kiri::render::Image image = r.render(cam, w, h);
    const auto row_luminance = [&](double z) {
        const int y = int(kiri::render::project_to_pixel(cam, {0.0, -300.0, z}, w, h).y);
        double sum = 0.0;
        for (int x = w / 4; x < 3 * w / 4; ++x) {
            const std::uint8_t* p = &image.rgba[(std::size_t(y) * w + x) * 4];
            sum += 0.3 * p[0] + 0.6 * p[1] + 0.1 * p[2];
        }
        return sum / (w / 2);
    };
    const double top = row_luminance(370.0), middle = row_luminance(300.0), bottom = row_luminance(230.0);
    EXPECT_GT(top, middle + 5.0) << top << " " << middle << " " << bottom;
    EXPECT_GT(middle, bottom + 5.0) << top << " " << middle << " " << bottom;
}
