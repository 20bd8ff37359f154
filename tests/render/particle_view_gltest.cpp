// What a billboard hides along each ray (particles.vert / particles.frag): the part of the
// particle's column between the eye and the terrain (footprint_ray_share), read back from the
// frame's linear radiance against the closed form, for a particle around the eye (its centre
// behind the eye: the whole screen), one cut by the ground, one farther off (a disc) and one
// astride the edge of the rectangle that holds the fog, one under a blanket's floor, one under a
// lake's top.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>

#include <glm/geometric.hpp>

#include "kiri/geometry/particles/particle_footprint.hpp"
#include "kiri/render/renderer.hpp"
#include "kiri/render/scene_rendering.hpp"
#include "render/render_fixture.hpp"

namespace {

namespace g = kiri::geometry;

class ParticleViewGl : public kiri::test::GlTest {};

struct Agreement {
    double mean = 0.0, worst = 0.0;
    int pixels = 0;
    double hidden = 0.0;  // the mean opacity the particle should show
};

// One black particle (albedo 0: it only hides what lies behind it) over flat ground, seen from
// 30 m up at 64x48: the frame without it (behind) and with it (seen), linear radiance, and the
// renderer that drew it (its pick).
struct OneParticle {
    kiri::render::Camera cam;
    int w = 64, h = 48;
    kiri::render::RadianceImage behind, seen;
    kiri::render::Renderer r;
};

std::unique_ptr<OneParticle> draw_one_particle(const g::Particle& particle, glm::dvec2 xy_min, glm::dvec2 xy_max,
                                               const glm::dvec3& target)
{
    auto d = std::make_unique<OneParticle>();
    const g::Terrain flat = kiri::test::gaussian_hill(33, 100.0, 0.0);
    d->cam.position = {0.0, 0.0, 30.0};
    d->cam.target = target;
    d->cam.fov_y_deg = 60.0;
    kiri::render::SunLight sun;
    sun.direction = glm::normalize(glm::dvec3(0.3, -0.4, 0.8));
    kiri::render::ParticleStyle style;
    style.near_scale = 1;  // every billboard at full resolution: the comparison is per pixel

    kiri::render::Renderer bare;
    bare.set_terrain(flat, 1.0, false);
    bare.set_sun(sun);
    bare.render(d->cam, d->w, d->h);
    d->behind = bare.read_radiance();

    g::ParticleCloud cloud;
    cloud.scattering_octaves = 1;
    cloud.particles.push_back(particle);
    cloud.fog_xy_min = xy_min;
    cloud.fog_xy_max = xy_max;
    d->r.set_terrain(flat, 1.0, false);
    d->r.set_sun(sun);
    d->r.set_particles(cloud, style);
    d->r.render(d->cam, d->w, d->h);
    d->seen = d->r.read_radiance();
    return d;
}

// The frame with the particle over the frame without it (draw_one_particle) is the transmittance
// T of each pixel's ray; the closed form is exp(-tau f(rho / r) share), the share of the column
// between the eye and the ground the ray meets there (pick), and over the fog's rectangle
// [xy_min, xy_max] and above the floor's plane (its height at the centre and its slope; the
// closed form's plane may be given another slope, `expected_slope`).
Agreement transmittance_agreement(const glm::dvec3& centre, double radius, double tau,
                                  glm::dvec2 xy_min = glm::dvec2(-1e300), glm::dvec2 xy_max = glm::dvec2(1e300),
                                  double above_ground = 1.0, double floor = -1e300,
                                  glm::dvec3 target = glm::dvec3(0.0, 200.0, 0.0), glm::dvec2 slope = glm::dvec2(0.0),
                                  std::optional<glm::dvec2> expected_slope = std::nullopt, double top = 1e300,
                                  glm::dvec2 top_slope = glm::dvec2(0.0))
{
    const glm::dvec2 plane = expected_slope.value_or(slope);
    const std::unique_ptr<OneParticle> d = draw_one_particle(
        {centre, radius, tau, 0.0, above_ground, floor, slope, top < 1e300 ? top : HUGE_VAL, top_slope}, xy_min, xy_max,
        target);
    const kiri::render::Camera& cam = d->cam;
    const int w = d->w, h = d->h;
    const kiri::render::RadianceImage &behind = d->behind, &seen = d->seen;
    kiri::render::Renderer& r = d->r;
    const g::ReferenceView view = kiri::render::reference_view(cam, w, h, 0.0);
    Agreement a;
    double sum = 0.0, hidden = 0.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = (std::size_t(y) * w + x) * 4 + 1;  // green
            if (!(behind.rgba[i] > 0.02f))
                continue;
            const glm::dvec3 ray = view.ray(x, y);
            const std::optional<glm::dvec3> ground = r.pick(x, y);
            double start = 0.0, end = ground ? glm::length(*ground - cam.position) : 1e9;
            for (int axis = 0; axis < 2; ++axis)
                if (ray[axis] != 0.0) {
                    const double a = (xy_min[axis] - cam.position[axis]) / ray[axis];
                    const double b = (xy_max[axis] - cam.position[axis]) / ray[axis];
                    start = std::max(start, std::min(a, b));
                    end = std::min(end, std::max(a, b));
                }
            // The part of the ray on the fog's side of a plane: the eye `inside` by that much, the
            // ray going further in at `rate`.
            const auto keep = [&](double inside, double rate) {
                if (rate > 0.0)
                    start = std::max(start, -inside / rate);
                else if (rate < 0.0)
                    end = std::min(end, -inside / rate);
                else if (inside < 0.0)
                    end = start;
            };
            // Above the fog's floor, z(t) >= floor + slope . (xy(t) - centre.xy), and under its top.
            keep(cam.position.z - floor - glm::dot(plane, glm::dvec2(cam.position - centre)),
                 ray.z - glm::dot(plane, glm::dvec2(ray)));
            keep(top + glm::dot(top_slope, glm::dvec2(cam.position - centre)) - cam.position.z,
                 glm::dot(top_slope, glm::dvec2(ray)) - ray.z);
            const glm::dvec3 to_centre = centre - cam.position;
            const double along = glm::dot(to_centre, ray);
            const double rho = std::sqrt(std::max(glm::dot(to_centre, to_centre) - along * along, 0.0));
            const double share = g::footprint_ray_share(rho / radius, radius, start - along, end - along);
            // The part in the ground adds to what the ray sees: tau / above_ground.
            const double expected = std::exp(-tau / above_ground * g::footprint_profile(rho / radius) * share);
            const double measured = double(seen.rgba[i]) / double(behind.rgba[i]);
            sum += std::abs(measured - expected);
            a.worst = std::max(a.worst, std::abs(measured - expected));
            hidden += 1.0 - expected;
            ++a.pixels;
        }
    a.mean = sum / std::max(a.pixels, 1);
    a.hidden = hidden / std::max(a.pixels, 1);
    return a;
}

// The optical depth one black particle spreads over the frame, summed over its pixels as
// -ln T times each pixel's solid angle (T: the frame with it over the frame without it), over
// what its ball holds seen from the eye: tau footprint_area r^2 / d^2 (1 when they agree).
double optical_mass_ratio(const glm::dvec3& centre, double radius, double tau)
{
    const std::unique_ptr<OneParticle> d = draw_one_particle(
        {centre, radius, tau, 0.0, 1.0, -1e300}, glm::dvec2(-1e300), glm::dvec2(1e300), glm::dvec3(0.0, 200.0, 0.0));
    const kiri::render::Camera& cam = d->cam;
    const int w = d->w, h = d->h;
    const kiri::render::RadianceImage &behind = d->behind, &seen = d->seen;
    const g::ReferenceView view = kiri::render::reference_view(cam, w, h, 0.0);
    const double pixel = 2.0 * std::tan(cam.fov_y_deg * std::numbers::pi / 360.0) / h;  // on the plane 1 m ahead
    double mass = 0.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = (std::size_t(y) * w + x) * 4 + 1;
            if (!(behind.rgba[i] > 0.02f) || !(seen.rgba[i] < behind.rgba[i]))
                continue;
            const double cos_off_axis = glm::dot(view.ray(x, y), view.forward());
            mass +=
                -std::log(double(seen.rgba[i]) / double(behind.rgba[i])) * pixel * pixel * std::pow(cos_off_axis, 3.0);
        }
    const double distance = glm::length(centre - cam.position);
    return mass / (tau * g::footprint_area() * radius * radius / (distance * distance));
}

}  // namespace

TEST_F(ParticleViewGl, AParticleAroundTheEyeHidesWhatLiesInFrontOfTheEye)
{
    // The centre 20 m behind the eye, radius 80 m: every ray from the eye crosses the front part
    // of the particle, more of it on rays towards the centre. A billboard at the centre would lie
    // behind the eye, and hide nothing.
    const Agreement a = transmittance_agreement({0.0, -20.0, 35.0}, 80.0, 2.0);
    EXPECT_GT(a.pixels, 64 * 48 * 9 / 10);
    EXPECT_GT(a.hidden, 0.15);
    EXPECT_LT(a.mean, 0.001) << a.worst;
    EXPECT_LT(a.worst, 0.01);
}

TEST_F(ParticleViewGl, AParticleHalfUnderTheGroundShowsTheColumnAboveIt)
{
    // In front of the eye, its centre 10 m under the ground: the rays that meet the ground within
    // it cross only the part in front of the ground.
    const Agreement a = transmittance_agreement({0.0, 150.0, -10.0}, 70.0, 3.0);
    EXPECT_GT(a.hidden, 0.05);
    EXPECT_LT(a.mean, 0.001) << a.worst;
    EXPECT_LT(a.worst, 0.01);
}

TEST_F(ParticleViewGl, AParticleHalfUnderTheGroundDrawsItsBuriedMassInThePartAbove)
{
    // The same particle with its share above the flat ground known (0.39 of its mass): the rays
    // see that part with the whole particle's mass, tau / 0.39.
    const glm::dvec3 centre(0.0, 150.0, -10.0);
    const double above = g::footprint_share_above(centre, 70.0, [](double, double) { return 0.0; });
    ASSERT_GT(above, 0.3);
    ASSERT_LT(above, 0.45);
    const Agreement a = transmittance_agreement(centre, 70.0, 3.0, glm::dvec2(-1e300), glm::dvec2(1e300), above);
    const Agreement drawn_as_before = transmittance_agreement(centre, 70.0, 3.0);
    EXPECT_GT(a.hidden, 1.5 * drawn_as_before.hidden);
    EXPECT_LT(a.mean, 0.001) << a.worst;
    EXPECT_LT(a.worst, 0.01);
}

TEST_F(ParticleViewGl, AParticleAtABlanketsBottomShowsNothingBelowIt)
{
    // A blanket's bottom 60 m over the ground, the eye under it at 30 m looking up at a particle
    // 30 m above the floor (radius 70 m: its ball reaches 40 m below the floor). The rays see only
    // the part over the floor; the part below it would veil the clear air under the blanket.
    const glm::dvec3 centre(0.0, 200.0, 90.0), up(0.0, 200.0, 120.0);
    const Agreement cut =
        transmittance_agreement(centre, 70.0, 2.0, glm::dvec2(-1e300), glm::dvec2(1e300), 1.0, 60.0, up);
    EXPECT_GT(cut.hidden, 0.05);
    EXPECT_LT(cut.mean, 0.001) << cut.worst;
    EXPECT_LT(cut.worst, 0.01);
    // The whole ball hides more: the floor is what cut it.
    const Agreement whole =
        transmittance_agreement(centre, 70.0, 2.0, glm::dvec2(-1e300), glm::dvec2(1e300), 1.0, -1e300, up);
    EXPECT_GT(whole.hidden, 1.1 * cut.hidden);
}

TEST_F(ParticleViewGl, AParticleUnderASlopingBottomShowsNothingBelowItsPlane)
{
    // The same under a bottom rising 1 in 4 across the view (its plane 60 m high at the
    // particle's centre): the rays see the ball over the sloping plane. The closed form cut at the
    // level plane through the centre is not what is drawn.
    const glm::dvec3 centre(0.0, 200.0, 90.0), up(0.0, 200.0, 120.0);
    const glm::dvec2 slope(0.25, 0.0);
    const Agreement cut =
        transmittance_agreement(centre, 70.0, 2.0, glm::dvec2(-1e300), glm::dvec2(1e300), 1.0, 60.0, up, slope);
    EXPECT_GT(cut.hidden, 0.05);
    EXPECT_LT(cut.mean, 0.001) << cut.worst;
    EXPECT_LT(cut.worst, 0.01);
    const Agreement level = transmittance_agreement(centre, 70.0, 2.0, glm::dvec2(-1e300), glm::dvec2(1e300), 1.0, 60.0,
                                                    up, slope, glm::dvec2(0.0));
    EXPECT_GT(level.mean, 0.002) << level.worst;  // measured 0.0041, worst 0.34
}

TEST_F(ParticleViewGl, AParticleUnderALakesTopShowsNothingAboveItsPlane)
{
    // A fog lake's top 20 m up, rising 1 in 4 across the view, the eye over it at 30 m looking
    // down at a particle 10 m under the top (radius 50 m: its ball stands 40 m out of it). The
    // rays see the ball under the plane; the part over it would veil what lies beyond the lake.
    const glm::dvec3 centre(0.0, 120.0, 10.0);
    const glm::dvec2 none(1e300);
    const Agreement cut = transmittance_agreement(centre, 50.0, 3.0, -none, none, 1.0, -1e300, {0.0, 120.0, 0.0},
                                                  glm::dvec2(0.0), std::nullopt, 20.0, {0.25, 0.0});
    EXPECT_GT(cut.hidden, 0.05);
    EXPECT_LT(cut.mean, 0.001) << cut.worst;
    EXPECT_LT(cut.worst, 0.01);
    // The whole ball hides more: the top is what cut it.
    const Agreement whole = transmittance_agreement(centre, 50.0, 3.0, -none, none, 1.0, -1e300, {0.0, 120.0, 0.0});
    EXPECT_GT(whole.hidden, 1.1 * cut.hidden);
}

TEST_F(ParticleViewGl, AFarParticleCoversItsWholeConeOfRays)
{
    // 3.3 radii off, above the ground: a disc facing the eye, wide enough that the rays at its rim
    // pass the radius from the centre.
    const Agreement a = transmittance_agreement({40.0, 400.0, 60.0}, 120.0, 2.0);
    EXPECT_GT(a.hidden, 0.05);
    EXPECT_LT(a.mean, 0.001) << a.worst;
    EXPECT_LT(a.worst, 0.01);
}

TEST_F(ParticleViewGl, AParticleAstrideTheFogsEdgeHidesNothingBeyondIt)
{
    // The fog ends at x = 20 m (the Medium's grid, a wall of fog), and the particle's centre lies
    // on that wall, seen at a slant: the rays take only the part of its column over the fog's
    // side, and what lies beyond the wall is not blurred by it.
    const Agreement a = transmittance_agreement({20.0, 200.0, 40.0}, 70.0, 3.0, {-1e4, -1e4}, {20.0, 1e4});
    const Agreement whole = transmittance_agreement({20.0, 200.0, 40.0}, 70.0, 3.0);
    EXPECT_GT(a.hidden, 0.05);
    EXPECT_LT(a.hidden, 0.8 * whole.hidden);
    EXPECT_LT(a.mean, 0.001) << a.worst;
    EXPECT_LT(a.worst, 0.01);
}

TEST_F(ParticleViewGl, AParticleNarrowerThanAPixelKeepsItsOpticalMass)
{
    // A ball 1.5 m across 300 m off spans a fifth of a pixel (7.2 m there): drawn as it is, a
    // pixel's centre either misses it (nothing) or meets its middle (the pixel's whole solid angle
    // at its central optical depth, 30 times its mass). Widened to a pixel with its optical depth
    // thinned alike, the pixels around it sum to its mass within a quarter wherever it falls
    // between their centres, and to its mass on average over where it falls (its optical depth
    // of 20 thinned to about 0.9: the frame's half floats keep -ln T to 0.1 %).
    double sum = 0.0;
    int n = 0;
    for (double across : {0.0, 1.8, 3.6, 5.4})
        for (double up : {0.0, 1.8, 3.6, 5.4}) {
            const double ratio = optical_mass_ratio({across, 300.0, 12.0 + up}, 1.5, 20.0);
            EXPECT_NEAR(ratio, 1.0, 0.25) << "shifted " << across << " m across, " << up << " m up";
            sum += ratio;
            ++n;
        }
    EXPECT_NEAR(sum / n, 1.0, 0.04);
    // Resting on the ground, seen at a slant (8 degrees): the pixels below it see the ground in
    // front of it, but what hides the ball is taken along the ray through its centre, which
    // passes it whole.
    for (double across : {0.0, 1.8, 3.6, 5.4}) {
        const double ratio = optical_mass_ratio({across, 200.0, 1.6}, 1.5, 20.0);
        EXPECT_NEAR(ratio, 1.0, 0.25) << "on the ground, shifted " << across << " m";
    }
}
