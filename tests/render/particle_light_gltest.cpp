// The billboards' per-particle light and their near resolution (render/src/particle_light.hpp,
// ParticleStyle::near_scale): the light a fragment reads through its particle's record and gain
// table against the same light computed in full and against the CPU twin (attenuation_cpu.hpp),
// the per-particle light rebuilt only when the sun or the particles change, and the near
// billboards' fragments bounded by their coarser target while the picture stays the same.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "geometry/particle_test_clouds.hpp"
#include "kiri/geometry/particles/attenuation_cpu.hpp"
#include "kiri/geometry/particles/particle_footprint.hpp"
#include "kiri/render/attenuation.hpp"
#include "kiri/render/renderer.hpp"
#include "particle_light.hpp"
#include "sun_volume.hpp"
#include "render/render_fixture.hpp"

namespace {

namespace g = kiri::geometry;
using kiri::render::AttenuationBuffer;
using kiri::render::detail::ParticleLight;

class ParticleLightGl : public kiri::test::GlTest {};

TEST_F(ParticleLightGl, TableReadsWhatTheFullSelfShadowReads)
{
    // Radius 30 m in a 32^3 grid over a 150 m ball: every footprint spans several columns, the
    // light is oblique (a sheared or tilted grid), R32F. Then the same balls cut at a tilted
    // top's plane and a floor's through the cloud: their own columns cut as their deposits are.
    for (const bool cut : {false, true}) {
        SCOPED_TRACE(cut ? "cut at planes" : "whole balls");
        g::ParticleCloud c = kiri::test::ball_cloud(400, 150.0, 30.0, 0.5);
        if (cut)
            for (std::size_t k = 0; k < c.particles.size(); ++k) {
                g::Particle& p = c.particles[k];
                p.top_slope = glm::dvec2(0.15, -0.1);
                p.top = 1060.0 + glm::dot(p.top_slope, glm::dvec2(p.position));
                p.above_ground = k % 2 ? 1.0 : 0.6;  // the share drawn, its cut given back
                if (k % 3 == 0)
                    p.floor = 920.0;
            }
        AttenuationBuffer b;
        b.set_particles(c);
        kiri::render::AttenuationOptions o;
        o.resolution = 32;
        o.half_float = false;
        ASSERT_TRUE(b.update({0.3, -0.5, 0.8}, o));
        ParticleLight light;
        ASSERT_TRUE(light.update(c, b, nullptr));
        ASSERT_TRUE(light.has_table());
        EXPECT_FALSE(light.update(c, b, nullptr));  // nothing changed

        // On each billboard: its centre and eight points at 0.3 and 0.7 of its radius, across the
        // light's columns.
        const std::vector<std::uint32_t>& index = b.particle_order();
        std::vector<glm::vec3> points;
        std::vector<std::uint32_t> slots;
        const glm::dvec3 across[4] = {{1, 0, 0}, {0, 1, 0}, {0.6, 0.0, 0.8}, {-0.48, 0.6, 0.64}};
        for (std::uint32_t k = 0; k < index.size(); ++k) {
            const g::Particle& p = c.particles[index[k]];
            points.push_back(glm::vec3(p.position - b.particle_centre()));
            slots.push_back(k);
            for (const glm::dvec3& a : across)
                for (double s : {0.3, -0.7}) {
                    points.push_back(glm::vec3(p.position + s * p.radius * a - b.particle_centre()));
                    slots.push_back(k);
                }
        }
        const std::vector<glm::vec2> read = light.sample_log_gamma(c, b, points, slots);
        ASSERT_EQ(read.size(), points.size());
        const g::AttenuationVolume cpu = g::build_attenuation_cpu(c, b.grid());
        double worst_table = 0.0, worst_cpu = 0.0, self_sum = 0.0, excess_sum = 0.0;
        for (std::size_t q = 0; q < points.size(); ++q) {
            // The same float operations on the same numbers, the gains read instead of computed.
            worst_table = std::max(worst_table, double(std::abs(read[q].x - read[q].y)));
            const g::Particle& p = c.particles[index[slots[q]]];
            const glm::dvec3 world = glm::dvec3(points[q]) + b.particle_centre();
            const double self = g::self_log_gamma(b.grid(), p, c.forward_scattering, world);
            const double twin = g::billboard_log_gamma(cpu, p, c.forward_scattering, world);
            worst_cpu = std::max(worst_cpu, std::abs(read[q].x - twin));
            self_sum += self;
            excess_sum += std::abs(
                self - g::billboard_own_share * g::own_column_log_gain(b.grid(), p, c.forward_scattering, world));
        }
        EXPECT_LT(worst_table, 1e-5);
        // The buffer's fixed-point rounding (BufferEqualsItsCpuTwin) and float against double.
        EXPECT_LT(worst_cpu, 60.0 / b.fixed_point_scale() + 1e-4);
        EXPECT_LT(self_sum / double(points.size()), -0.05);  // the own cylinder is there to take out
        // and the share of the own column to put back differs from it (points up-sun of the centre)
        EXPECT_GT(excess_sum / double(points.size()), 0.02);
    }
}

TEST_F(ParticleLightGl, BillboardsInAFogAParticleDeepReadTheMediumsOpticalDepthAtTheirCentres)
{
    // A uniform slab 120 m deep, its particles of about 100 m radius (a valley lake's are as large as it is
    // deep): the buffer's read at a centre falls short of the Medium's optical depth towards the
    // sun by more than half the particle's own column, what the blue-noise sampler keeps empty
    // around it. Measured against the Medium through the sun volume, each particle's own share
    // makes it up (particle_light.comp); the CPU twin agrees (calibrated_own_share).
    const double sigma = 0.02, bottom = 100.0, top = 220.0, side = 3000.0;
    const g::Medium m = kiri::test::slab_medium(side, bottom, top, true, sigma);
    g::ParticleOptions o;
    o.count = 3000;
    g::ParticleCloud c = g::sample_particles(m, o);
    for (g::Particle& p : c.particles) {
        p.top = top;
        p.floor = bottom;
        p.above_ground = g::footprint_share_between(p.position, p.radius, [&](double, double) {
            return std::pair{bottom, top};
        });
    }
    const glm::dvec3 sun = glm::normalize(glm::dvec3(0.6, 0.8, 1.1));
    AttenuationBuffer b;
    b.set_particles(c);
    kiri::render::AttenuationOptions ao;
    ao.resolution = 96;
    ao.half_float = false;
    ASSERT_TRUE(b.update(sun, ao));
    kiri::render::detail::SunVolume volume;
    volume.set(&m, {});
    volume.update(glm::vec3(sun));
    ASSERT_TRUE(volume.ready());
    const g::AttenuationVolume cpu = g::build_attenuation_cpu(c, b.grid());
    const std::vector<std::uint32_t>& index = b.particle_order();
    std::vector<glm::vec3> points;
    std::vector<std::uint32_t> slots;
    for (std::uint32_t k = 0; k < index.size(); ++k) {
        const g::Particle& p = c.particles[index[k]];
        if (std::max(std::abs(p.position.x), std::abs(p.position.y)) > 0.5 * side - 500.0)
            continue;  // the sun's path leaves through the top
        points.push_back(glm::vec3(p.position - b.particle_centre()));
        slots.push_back(k);
    }
    ASSERT_GT(points.size(), 500u);
    double medium = 0.0, fixed = 0.0, measured = 0.0, twin = 0.0, worst_twin = 0.0;
    for (const bool calibrate : {false, true}) {
        ParticleLight light;
        ASSERT_TRUE(light.update(c, b, nullptr, calibrate ? &volume : nullptr));
        const std::vector<glm::vec2> read = light.sample_log_gamma(c, b, points, slots);
        ASSERT_EQ(read.size(), points.size());
        for (std::size_t q = 0; q < points.size(); ++q) {
            const g::Particle& p = c.particles[index[slots[q]]];
            const double tau = sigma * (top - p.position.z) / sun.z;
            (calibrate ? measured : fixed) -= read[q].x;
            if (!calibrate) {
                medium += tau;
                continue;
            }
            const double share = g::calibrated_own_share(cpu, p, c.forward_scattering, tau);
            const double cpu_read = g::billboard_log_gamma(cpu, p, c.forward_scattering, p.position, share);
            twin -= cpu_read;
            worst_twin = std::max(worst_twin, std::abs(cpu_read - read[q].x) / std::max(tau, 0.1));
        }
    }
    const double n = double(points.size());
    std::printf(
        "    at the centres: the Medium %.4f; the billboards %.4f (half the own column: %.4f); the CPU twin "
        "%.4f, worst %.4f\n",
        medium / n, measured / n, fixed / n, twin / n, worst_twin);
    EXPECT_LT(std::abs(fixed / medium - 1.0), 0.2);
    EXPECT_GT(std::abs(fixed / medium - 1.0), 0.05);
    EXPECT_NEAR(measured / medium, 1.0, 0.02);
    EXPECT_NEAR(twin / medium, 1.0, 0.01);
    EXPECT_LT(worst_twin, 0.05);
}

// A ball of particles 400 m over flat ground, and an eye inside it.
g::ParticleCloud raised_ball(int n, double tau)
{
    g::ParticleCloud c = kiri::test::ball_cloud(n, 150.0, 30.0, tau);
    for (g::Particle& p : c.particles)
        p.position.z -= 600.0;  // the ball_cloud is centred 1000 m up
    return c;
}
kiri::render::Camera eye_in()
{
    kiri::render::Camera cam;
    cam.position = {0.0, -60.0, 400.0};
    cam.target = {0.0, 100.0, 390.0};
    cam.fov_y_deg = 60.0;
    return cam;
}

TEST_F(ParticleLightGl, RebuiltOnlyWhenTheSunOrTheParticlesChange)
{
    g::ParticleCloud c = raised_ball(300, 0.5);
    kiri::render::Renderer r;
    r.set_terrain(kiri::test::gaussian_hill(33, 100.0, 0.0), 1.0, false);
    r.set_particles(c);
    kiri::render::Camera cam = eye_in();
    r.draw(cam, 64, 48);
    EXPECT_EQ(r.last_stats().particle_light_rebuilds, 1);
    r.draw(cam, 64, 48);  // a still view
    EXPECT_EQ(r.last_stats().particle_light_rebuilds, 0);
    for (int frame = 0; frame < 3; ++frame) {  // a moving eye
        cam.position.x += 5.0;
        r.draw(cam, 64, 48);
        EXPECT_EQ(r.last_stats().particle_light_rebuilds, 0);
    }
    kiri::render::SunLight sun;
    sun.direction = {0.2, 0.1, 1.0};
    r.set_sun(sun);
    r.draw(cam, 64, 48);
    EXPECT_EQ(r.last_stats().particle_light_rebuilds, 1);
    c.particles[3].position.z += 2.0;
    r.set_particles(c);
    r.draw(cam, 64, 48);
    EXPECT_EQ(r.last_stats().particle_light_rebuilds, 1);
    r.draw(cam, 64, 48);
    EXPECT_EQ(r.last_stats().particle_light_rebuilds, 0);
}

double mean_difference(const kiri::render::Image& a, const kiri::render::Image& b)
{
    double sum = 0.0;
    for (std::size_t i = 0; i < a.rgba.size(); ++i)
        sum += std::abs(int(a.rgba[i]) - int(b.rgba[i]));
    return sum / double(a.rgba.size());
}

TEST_F(ParticleLightGl, BillboardsOutOfViewAreLeftOutAndTheFrameIsTheSame)
{
    // The eye inside the cloud, some of it behind, beside, above and below the view: those
    // billboards are not drawn; every one that reaches a pixel is, so the frame is the same to
    // the bit as with every billboard drawn.
    const g::ParticleCloud c = raised_ball(300, 0.3);
    const g::Terrain ground = kiri::test::gaussian_hill(33, 100.0, 0.0);
    kiri::render::Camera cam = eye_in();
    cam.fov_y_deg = 40.0;
    const int w = 96, h = 64;
    const auto draw = [&](bool cull, kiri::render::RadianceImage* out) {
        kiri::render::Renderer r;
        r.set_terrain(ground, 1.0, false);
        kiri::render::ParticleStyle style;
        style.cull_outside_view = cull;
        r.set_particles(c, style);
        r.draw(cam, w, h);
        *out = r.read_radiance();
        return r.last_stats();
    };
    kiri::render::RadianceImage all, culled;
    const kiri::render::FrameStats every = draw(false, &all), in_view = draw(true, &culled);
    EXPECT_EQ(every.particles_drawn, int(c.particles.size()));
    // The centres within the view's pyramid are the least that must be drawn.
    const glm::dvec3 f = glm::normalize(cam.target - cam.position);
    const double tan_y = std::tan(0.5 * cam.fov_y_deg * 3.14159265358979 / 180.0), tan_x = tan_y * w / h;
    const glm::dvec3 right = glm::normalize(glm::cross(f, glm::dvec3(0, 0, 1))), up = glm::cross(right, f);
    int centres_in_view = 0;
    for (const g::Particle& p : c.particles) {
        const glm::dvec3 v = p.position - cam.position;
        const double depth = glm::dot(v, f);
        centres_in_view +=
            depth > 0.0 && std::abs(glm::dot(v, right)) < depth * tan_x && std::abs(glm::dot(v, up)) < depth * tan_y;
    }
    ASSERT_GT(centres_in_view, 30);
    EXPECT_GE(in_view.particles_drawn, centres_in_view);
    EXPECT_LT(in_view.particles_drawn, int(0.8 * c.particles.size()));
    ASSERT_EQ(all.rgba.size(), culled.rgba.size());
    EXPECT_TRUE(all.rgba == culled.rgba);
}

TEST_F(ParticleLightGl, NearBillboardsDrawCoarserAndLookTheSame)
{
    // The eye inside a cloud: billboards fill the view, each with little opacity.
    const g::ParticleCloud c = raised_ball(300, 0.2);
    const g::Terrain ground = kiri::test::gaussian_hill(33, 100.0, 0.0);
    const kiri::render::Camera cam = eye_in();
    const int w = 96, h = 64;
    const auto draw = [&](int near_scale, kiri::render::Image* image) {
        kiri::render::Renderer r;
        r.set_terrain(ground, 1.0, false);
        kiri::render::ParticleStyle style;
        style.near_scale = near_scale;
        style.near_pixels = 8.0;
        r.set_particles(c, style);
        *image = r.render(cam, w, h);
        return r.last_stats();
    };
    kiri::render::Image full, half, quarter;
    const kiri::render::FrameStats at_full = draw(1, &full), at_half = draw(2, &half), at_quarter = draw(4, &quarter);
    EXPECT_EQ(at_full.near_particles, 0);
    // The billboards in view nearer than r P / near_pixels (P = h / 2 / tan 30 deg = 55 px):
    // 206 m, most of those in view.
    EXPECT_EQ(at_half.particles_drawn, at_full.particles_drawn);
    ASSERT_GT(at_half.near_particles, at_half.particles_drawn / 2);
    EXPECT_EQ(at_quarter.near_particles, at_half.near_particles);
    const std::uint64_t far = std::uint64_t(at_half.particles_drawn - at_half.near_particles);
    // Each near billboard blends at most the whole coarse target, each far one the frame.
    EXPECT_LE(at_half.particle_fragments, std::uint64_t(at_half.near_particles) * (w / 2) * (h / 2) + far * w * h);
    EXPECT_LE(at_quarter.particle_fragments,
              std::uint64_t(at_quarter.near_particles) * (w / 4) * (h / 4) + far * w * h);
    EXPECT_GT(at_full.particle_fragments, 3 * at_half.particle_fragments);
    EXPECT_GT(at_half.particle_fragments, 3 * at_quarter.particle_fragments);
    // The same fog: its opacity and light are smooth at the coarse pixels' scale.
    // The same fog (a mean of 7 grey levels over the bare ground): its opacity and light are
    // smooth at the coarse pixels' scale, and the layers compose exactly.
    EXPECT_LT(mean_difference(full, half), 0.5);
    EXPECT_LT(mean_difference(full, quarter), 1.0);
    kiri::render::Renderer bare;
    bare.set_terrain(ground, 1.0, false);
    EXPECT_GT(mean_difference(full, bare.render(cam, w, h)), 5.0);  // there is fog to see
}

TEST_F(ParticleLightGl, AFrameDrawnSmallDrawsFewerWiderBillboardsOfTheSameMass)
{
    // The cloud from outside, at a small frame as the preview draws while the view moves: at an
    // eighth of the still's size every 4th billboard, twice as wide with its optical depth. The
    // fog it adds over the bare ground (summed radiance) is the whole cloud's; drawn as a
    // quarter of the billboards at their own size it would be a quarter of it (shown so: 0.30).
    // A semi-transparent cloud (optical depth about 1 across): an opaque one's rim widens by the
    // billboards' extra radius, which at the preview's floor is a pixel or two.
    g::ParticleCloud c = kiri::test::ball_cloud(3000, 400.0, 25.0, 0.1);
    for (g::Particle& p : c.particles)
        p.position.z -= 400.0;
    const g::Terrain ground = kiri::test::gaussian_hill(33, 100.0, 0.0);
    kiri::render::Camera cam;
    cam.position = {-1500.0, -1200.0, 900.0};
    cam.target = {0.0, 0.0, 600.0};
    cam.fov_y_deg = 40.0;
    const int w = 80, h = 45;
    const auto fog_added = [&](double scale, int* drawn) {
        kiri::render::Renderer r;
        r.set_terrain(ground, 1.0, false);
        r.draw(cam, w, h);
        const kiri::render::RadianceImage bare = r.read_radiance();
        r.set_particles(c);
        r.set_particle_resolution(scale);
        r.draw(cam, w, h);
        *drawn = r.last_stats().particles_drawn;
        const kiri::render::RadianceImage fog = r.read_radiance();
        double sum = 0.0;
        for (std::size_t i = 0; i < fog.rgba.size(); i += 4)
            sum += std::abs(fog.rgba[i + 1] - bare.rgba[i + 1]);
        return sum;
    };
    int all = 0, half = 0, eighth = 0;
    const double whole = fog_added(1.0, &all), at_half = fog_added(0.5, &half), at_eighth = fog_added(0.125, &eighth);
    ASSERT_GT(all, 1000);
    EXPECT_EQ(half, all);  // from half the size on, every billboard
    EXPECT_NEAR(double(eighth), all / 4.0, 0.05 * all);
    EXPECT_DOUBLE_EQ(at_half, whole);
    std::printf("    fog added over the ground: every billboard %.2f, every 4th twice as wide %.2f\n", whole,
                at_eighth);
    EXPECT_NEAR(at_eighth / whole, 1.0, 0.05);
}

}  // namespace
