// The CPU reference ray marcher (reference_fog.hpp) against closed forms: homogeneous slabs
// lit by the sky and by the sun through the fog, the layer profile, height fog, a ridge's
// shadow in the fog; its own convergence on a noisy medium; determinism across threads.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "fog_test_terrains.hpp"
#include "kiri/geometry/medium/medium.hpp"
#include "kiri/geometry/reference/reference_fog.hpp"
#include "kiri/geometry/terrain/ground.hpp"
#include "slab_medium.hpp"

using namespace kiri::geometry;

namespace {

// A slab of fog between z = bottom and z = top over [-half, half]^2 (a 3 x 3 grid).
Medium slab(double bottom, double top, double sigma, double top_density = 1.0, double albedo = 0.9, double g = 0.5,
            double half = 5000.0, double detail = 0.0)
{
    MediumGrid grid;
    grid.nx = grid.ny = 3;
    grid.x0 = grid.y0 = -half;
    grid.dx = grid.dy = half;
    grid.floor.assign(9, bottom);
    grid.bottom.assign(9, bottom);
    grid.top.assign(9, top);
    grid.coverage.assign(9, 1.0);
    MediumOptions o;
    o.extinction = sigma;
    o.albedo = albedo;
    o.anisotropy = g;
    o.top_density = top_density;
    MediumDetail d;
    d.detail = detail;
    d.detail_scale = 200.0;
    return Medium(std::move(grid), o, d);
}

Heightfield flat(double z = 0.0, double half = 5000.0, int n = 11)
{
    return kiri::test::make_heightfield(n, n, 2.0 * half / (n - 1), -half, -half, [z](double, double) { return z; });
}

using kiri::test::expect_rel;
using kiri::test::sky_only;

}  // namespace

TEST(ReferenceFog, HomogeneousSlabLitByTheSky)
{
    // Inside a homogeneous medium over a distance D: T = exp(-sigma D), L = a L_amb (1 - T).
    const double sigma = 0.02, a = 0.9, d = 150.0;
    const Medium m = slab(0.0, 100.0, sigma, 1.0, a);
    const FogLighting light = sky_only();
    const RayFog r = reference_ray({&m, {}}, nullptr, {0.0, 0.0, 50.0}, {1.0, 0.0, 0.0}, d, light);
    EXPECT_NEAR(r.transmittance, std::exp(-sigma * d), 1e-12);
    expect_rel(r.inscatter, a * light.ambient * (1.0 - std::exp(-sigma * d)), 1e-9);
    EXPECT_FALSE(r.hit_terrain);
}

TEST(ReferenceFog, HomogeneousSlabLitByTheSunThroughTheFog)
{
    // A level ray at height z in a slab [0, H] with the sun at elevation e: every point sees
    // the sun through (H - z) / sin(e) of fog, so T_sun is constant along the ray.
    const double sigma = 0.01, a = 0.95, g = 0.7, H = 100.0, z = 40.0, d = 300.0, e = 0.4;
    const Medium m = slab(0.0, H, sigma, 1.0, a, g);
    FogLighting light;
    light.sun_direction = {std::cos(e), 0.0, std::sin(e)};
    light.sun_radiance = {3.0, 2.0, 1.0};
    light.ambient = {0.1, 0.2, 0.3};
    light.terrain_shadows = false;
    const glm::dvec3 w(0.0, 1.0, 0.0);
    const RayFog r = reference_ray({&m, {}}, nullptr, {0.0, 0.0, z}, w, d, light);
    const double t_sun = std::exp(-sigma * (H - z) / std::sin(e));
    const double phase = henyey_greenstein(glm::dot(w, light.sun_direction), g);
    const glm::dvec3 expected =
        a * (std::numbers::pi * light.sun_radiance * t_sun * phase + light.ambient) * (1.0 - std::exp(-sigma * d));
    // The one lighting model (fog_lighting.hpp) says the same, at one octave and at three.
    MediumOptions optics;
    optics.albedo = a;
    optics.anisotropy = g;
    optics.multiple_scattering = MultipleScattering::octaves;
    optics.scattering_octaves = 1;
    const FogLight fl{light.sun_radiance, light.ambient, std::sin(e)};
    expect_rel(fog_source(fl, optics, glm::dot(w, light.sun_direction), sigma * (H - z) / std::sin(e)) *
                   (1.0 - std::exp(-sigma * d)),
               expected, 1e-12);
    light.scattering_octaves = optics.scattering_octaves = 3;
    const RayFog r3 = reference_ray({&m, {}}, nullptr, {0.0, 0.0, z}, w, d, light);
    expect_rel(r3.inscatter,
               fog_source(fl, optics, glm::dot(w, light.sun_direction), sigma * (H - z) / std::sin(e)) *
                   (1.0 - std::exp(-sigma * d)),
               1e-9);
    // And with the fitted multiple scattering.
    light.multiple_scattering = optics.multiple_scattering = MultipleScattering::fitted;
    const RayFog rf = reference_ray({&m, {}}, nullptr, {0.0, 0.0, z}, w, d, light);
    expect_rel(rf.inscatter,
               fog_source(fl, optics, glm::dot(w, light.sun_direction), sigma * (H - z) / std::sin(e)) *
                   (1.0 - std::exp(-sigma * d)),
               1e-9);
    expect_rel(r.inscatter, expected, 1e-9);
    EXPECT_NEAR(r.transmittance, std::exp(-sigma * d), 1e-12);
}

TEST(ReferenceFog, DeepInADenseSlabTheSunsLightIsTheModels)
{
    // 80 m under the top of a fog of 0.1 per metre, the sun 22.9 degrees up: tau_sun = 20.5.
    // Single scattering has e^-20.5 of the sun left there, but the fitted model's light scattered
    // many times falls as e^-(1 - b) tau (b = 0.73) and the octaves' last as e^-tau / 4: the
    // reference marched tau_sun only to 12 and lit the point as if it lay at 12 (the fitted
    // model's sun there 10 times too bright). Now to 12 / sun_scattering_decay.
    const double sigma = 0.1, a = 0.95, g = 0.7, H = 100.0, z = 20.0, d = 300.0, e = 0.4;
    const Medium m = slab(0.0, H, sigma, 1.0, a, g);
    FogLighting light;
    light.sun_direction = {std::cos(e), 0.0, std::sin(e)};
    light.sun_radiance = {3.0, 2.0, 1.0};
    light.ambient = glm::dvec3(0.0);
    light.terrain_shadows = false;
    const glm::dvec3 w(0.0, 1.0, 0.0);
    const double tau_sun = sigma * (H - z) / std::sin(e);
    ASSERT_GT(tau_sun, 20.0);
    MediumOptions optics;
    optics.albedo = a;
    optics.anisotropy = g;
    const FogLight fl{light.sun_radiance, light.ambient, std::sin(e)};
    for (const auto kind : {MultipleScattering::fitted, MultipleScattering::octaves}) {
        light.multiple_scattering = optics.multiple_scattering = kind;
        light.scattering_octaves = optics.scattering_octaves = 3;
        const RayFog r = reference_ray({&m, {}}, nullptr, {0.0, 0.0, z}, w, d, light);
        expect_rel(r.inscatter,
                   fog_source(fl, optics, glm::dot(w, light.sun_direction), tau_sun) * (1.0 - std::exp(-sigma * d)),
                   1e-4);  // the ray stops where its transmittance falls under 1e-5
    }
}

TEST(ReferenceFog, LookingDownThroughASlabWithTheSunOverhead)
{
    // Eye at 2H looking straight down onto flat ground at 0, sun at the zenith: a point at
    // depth u under the top is lit through u of fog and seen through u of fog, so
    // L = a pi E p(-1) (1 - exp(-2 sigma H)) / 2 + a L_amb (1 - exp(-sigma H)) (pi E: fog_lighting.hpp).
    const double sigma = 0.015, a = 0.8, g = 0.3, H = 120.0;
    const Medium m = slab(0.0, H, sigma, 1.0, a, g);
    const Heightfield ground = flat();
    FogLighting light;
    light.sun_direction = {0.0, 0.0, 1.0};
    light.sun_radiance = glm::dvec3(2.5);
    light.ambient = {0.2, 0.25, 0.3};
    const RayFog r = reference_ray({&m, {}}, &ground, {10.0, 20.0, 2.0 * H}, {0.0, 0.0, -1.0}, 1e6, light);
    ASSERT_TRUE(r.hit_terrain);
    EXPECT_NEAR(r.distance, 2.0 * H, 1e-9);
    const glm::dvec3 expected = a * std::numbers::pi * light.sun_radiance * henyey_greenstein(-1.0, g) * 0.5 *
            (1.0 - std::exp(-2.0 * sigma * H)) +
        a * light.ambient * (1.0 - std::exp(-sigma * H));
    expect_rel(r.inscatter, expected, 2e-4);
    EXPECT_NEAR(r.transmittance, std::exp(-sigma * H), 1e-12);
}

TEST(ReferenceFog, TheGroundUnderTheFogLiesInItsShade)
{
    // Flat ground under a slab, the sun at the zenith, no sky: the ground gets e^-(sigma H) of the
    // sun, and fog_shade holds what the fog took, so fog_shade / surface = e^(sigma H) - 1.
    const double sigma = 0.015, H = 120.0;
    const Medium m = slab(0.0, H, sigma);
    const Heightfield ground = flat();
    FogLighting light;
    light.sun_direction = {0.0, 0.0, 1.0};
    light.sun_radiance = glm::dvec3(2.5);
    light.ambient = glm::dvec3(0.0);
    light.sky = false;
    const RayFog r = reference_ray({&m, {}}, &ground, {10.0, 20.0, 2.0 * H}, {0.0, 0.0, -1.0}, 1e6, light);
    ASSERT_TRUE(r.hit_terrain);
    ASSERT_GT(luminance(r.surface), 0.0);
    expect_rel(r.fog_shade, r.surface * std::expm1(sigma * H), 1e-3);  // the sun is traced from a cm above it
    // Without fog nothing is shaded.
    const RayFog bare = reference_ray({}, &ground, {10.0, 20.0, 2.0 * H}, {0.0, 0.0, -1.0}, 1e6, light);
    EXPECT_EQ(bare.fog_shade, glm::dvec3(0.0));
    expect_rel(bare.surface, r.surface + r.fog_shade, 1e-9);
}

TEST(ReferenceFog, LayerProfileOpticalDepth)
{
    // Density 1 - (1 - td) h: straight down through the shell, tau = sigma H (1 + td) / 2.
    const double sigma = 0.02, H = 80.0, td = 0.1;
    const Medium m = slab(10.0, 10.0 + H, sigma, td);
    const RayFog r = reference_ray({&m, {}}, nullptr, {0.0, 0.0, 500.0}, {0.0, 0.0, -1.0}, 600.0, sky_only());
    EXPECT_NEAR(r.transmittance, std::exp(-sigma * H * (1.0 + td) / 2.0), 1e-10);
    // A slanted ray sees 1 / cos of it.
    const glm::dvec3 w = glm::normalize(glm::dvec3(0.6, 0.0, -0.8));
    const RayFog s = reference_ray({&m, {}}, nullptr, {-300.0, 0.0, 500.0}, w, 1e4, sky_only());
    EXPECT_NEAR(s.transmittance, std::exp(-sigma * H * (1.0 + td) / 2.0 / 0.8), 1e-10);
}

TEST(ReferenceFog, HeightFogClosedForms)
{
    HeightFog f;
    f.extinction = 0.01;
    f.base = 100.0;
    f.scale_height = 50.0;
    // Vertical, from under the base to infinity: sigma0 (base - z0) + sigma0 H.
    EXPECT_NEAR(f.optical_depth({0, 0, 60.0}, {0, 0, 1}, 0.0, INFINITY), 0.01 * 40.0 + 0.01 * 50.0, 1e-14);
    // Level: sigma(z) times the length, also for a nearly level ray.
    EXPECT_NEAR(f.optical_depth({0, 0, 150.0}, {1, 0, 0}, 0.0, 1000.0), 0.01 * std::exp(-1.0) * 1000.0, 1e-12);
    EXPECT_NEAR(f.optical_depth({0, 0, 150.0}, glm::normalize(glm::dvec3(1, 0, 1e-9)), 0.0, 1000.0),
                0.01 * std::exp(-1.0) * 1000.0 * (1.0 - 0.5e-6 / 50.0), 1e-12);
    // Slanted segments agree with a fine midpoint rule.
    const glm::dvec3 o(0, 0, 20.0), d = glm::normalize(glm::dvec3(1.0, 0.5, 0.3));
    double sum = 0.0;
    const int n = 200000;
    for (int k = 0; k < n; ++k)
        sum += f.sigma(o.z + d.z * (k + 0.5) * 800.0 / n) * 800.0 / n;
    EXPECT_NEAR(f.optical_depth(o, d, 0.0, 800.0), sum, 1e-9);
    EXPECT_EQ(f.optical_depth(o, {0, 0, -1}, 0.0, INFINITY), INFINITY);

    // The marcher with height fog alone: a level ray, T = exp(-sigma(z) D) and the sky term.
    HeightFog h = f;
    h.albedo = 0.7;
    const FogLighting light = sky_only();
    const RayFog r = reference_ray({nullptr, h}, nullptr, {0.0, 0.0, 130.0}, {0.0, 1.0, 0.0}, 2000.0, light);
    const double s = h.sigma(130.0);
    EXPECT_NEAR(r.transmittance, std::exp(-s * 2000.0), 1e-10);
    expect_rel(r.inscatter, 0.7 * light.ambient * (1.0 - std::exp(-s * 2000.0)), 1e-6);
}

TEST(ReferenceFog, RidgeShadowInTheFog)
{
    // A knife-edge ridge (height R at x = 0) with the sun low in the -x direction: a level ray
    // at height z along +x sees the sun hidden for 0 < x < (R - z) / tan(e), so the sun's
    // in-scattering is a (1 - exp) integral with that gap cut out.
    const double sigma = 0.004, a = 1.0, R = 200.0, z = 50.0, e = 0.3;
    const Medium m = slab(0.0, 400.0, sigma, 1.0, a, 0.0);
    const Heightfield ridge = kiri::test::make_heightfield(
        401, 5, 10.0, -2000.0, -20.0, [R](double x, double) { return std::abs(x) < 1e-9 ? R : 0.0; });
    FogLighting light;
    light.sun_direction = {-std::cos(e), 0.0, std::sin(e)};
    light.sun_radiance = glm::dvec3(4.0);
    light.ambient = glm::dvec3(0.0);
    light.fog_shadows = false;
    const double x0 = -500.0, d = 2000.0;
    const RayFog r = reference_ray({&m, {}}, &ridge, {x0, 0.0, z}, {1.0, 0.0, 0.0}, d, light);
    // The ridge is a tent 20 m wide at its foot (grid spacing 10 m): the level ray at z = 50
    // meets its windward flank where R (1 - |x| / 10) = z, at x = -7.5.
    ASSERT_TRUE(r.hit_terrain);
    const double t_hit = -x0 - 10.0 * (1.0 - z / R);
    EXPECT_NEAR(r.distance, t_hit, 1e-9);
    // Everything before the hit is lit: L = a sigma pi E p ∫_0^t_hit exp(-sigma t) dt.
    const double p = std::numbers::pi / (4.0 * std::numbers::pi);  // pi E p_HG(g = 0) (fog_lighting.hpp)
    EXPECT_NEAR(r.inscatter.x, a * 4.0 * p * (1.0 - std::exp(-sigma * t_hit)), 1e-9);

    // From behind the ridge looking away from it, starting in its shadow.
    const double x_s = (R - z) / std::tan(e);
    const RayFog s = reference_ray({&m, {}}, &ridge, {20.0, 0.0, z}, {1.0, 0.0, 0.0}, d, light);
    EXPECT_FALSE(s.hit_terrain);
    const double lit_from = x_s - 20.0;
    const double expected = a * 4.0 * p * (std::exp(-sigma * lit_from) - std::exp(-sigma * d));
    EXPECT_NEAR(s.inscatter.x, expected, 1e-6 * expected);
    // With the shadow off the whole ray is lit.
    light.terrain_shadows = false;
    const RayFog u = reference_ray({&m, {}}, &ridge, {20.0, 0.0, z}, {1.0, 0.0, 0.0}, d, light);
    EXPECT_NEAR(u.inscatter.x, a * 4.0 * p * (1.0 - std::exp(-sigma * d)), 1e-9);
}

TEST(ReferenceFog, ConvergesOnANoisyMedium)
{
    // Noise and the layer profile, sun through the fog: halving every step changes the
    // answer by far less than the 2 % the froxels are judged at.
    const Medium m = slab(0.0, 150.0, 0.02, 0.1, 0.99, 0.8, 3000.0, 0.6);
    const Heightfield ground = kiri::test::make_heightfield(61, 61, 100.0, -3000.0, -3000.0, [](double x, double y) {
        return 60.0 + 50.0 * std::sin(x / 400.0) * std::cos(y / 500.0);
    });
    FogLighting light;
    light.sun_direction = {-0.7, 0.3, 0.35};
    ReferenceOptions coarse, fine;
    fine.optical_step = coarse.optical_step / 4.0;
    fine.knot_optical_step = coarse.knot_optical_step / 4.0;
    fine.shadow_optical_step = coarse.shadow_optical_step / 4.0;
    fine.feature_fraction = coarse.feature_fraction / 4.0;
    fine.shadow_feature_fraction = coarse.shadow_feature_fraction / 4.0;
    for (const glm::dvec3 dir :
         {glm::dvec3(0.8, 0.5, -0.2), glm::dvec3(-0.3, 0.9, -0.1), glm::dvec3(0.2, -0.1, -0.6)}) {
        const glm::dvec3 w = glm::normalize(dir);
        const RayFog a = reference_ray({&m, {}}, &ground, {-200.0, -300.0, 300.0}, w, 1e5, light, coarse);
        const RayFog b = reference_ray({&m, {}}, &ground, {-200.0, -300.0, 300.0}, w, 1e5, light, fine);
        EXPECT_GT(luminance(b.inscatter), 0.01);
        EXPECT_NEAR(luminance(a.inscatter), luminance(b.inscatter), 2e-3 * luminance(b.inscatter));
        EXPECT_NEAR(a.transmittance, b.transmittance, 2e-3 * b.transmittance + 1e-7);
        EXPECT_GT(b.steps, a.steps);
    }
}

TEST(ReferenceFog, ImagesAreDeterministicAcrossThreadsAndFinite)
{
    const Medium m = slab(0.0, 150.0, 0.02, 0.1, 0.99, 0.999999, 3000.0, 0.6);
    const Heightfield ground = kiri::test::make_heightfield(31, 31, 200.0, -3000.0, -3000.0, [](double x, double y) {
        return 80.0 + 120.0 * std::exp(-(x * x + y * y) / 1e6);
    });
    ReferenceView view;
    view.eye = {-2500.0, -2500.0, 400.0};
    view.target = {0.0, 0.0, 50.0};
    view.width = 24;
    view.height = 14;
    FogLighting light;
    light.sun_direction = {0.3, 0.2, 0.1};  // low, towards the camera: g near 1 at its peak
    ReferenceOptions one, two;
    one.threads = 1;
    two.threads = 2;
    const ReferenceImage a = render_reference_fog({&m, {}}, &ground, view, light, one);
    const ReferenceImage b = render_reference_fog({&m, {}}, &ground, view, light, two);
    ASSERT_EQ(a.inscatter.size(), std::size_t(24 * 14));
    for (std::size_t k = 0; k < a.inscatter.size(); ++k) {
        EXPECT_EQ(a.inscatter[k], b.inscatter[k]);
        EXPECT_EQ(a.transmittance[k], b.transmittance[k]);
        for (int c = 0; c < 3; ++c) {
            EXPECT_TRUE(std::isfinite(a.inscatter[k][c]));
            EXPECT_TRUE(std::isfinite(a.background[k][c]));
        }
        EXPECT_GE(a.transmittance[k], 0.0);
        EXPECT_LE(a.transmittance[k], 1.0);
    }
}

TEST(ReferenceFog, NoFogIsExactlyNothing)
{
    const Heightfield ground = flat();
    ReferenceView view;
    view.eye = {0.0, -2000.0, 500.0};
    view.width = 8;
    view.height = 6;
    const ReferenceImage r = render_reference_fog({}, &ground, view, FogLighting{});
    for (std::size_t k = 0; k < r.inscatter.size(); ++k) {
        EXPECT_EQ(r.inscatter[k], glm::dvec3(0.0));
        EXPECT_EQ(r.transmittance[k], 1.0);
        EXPECT_EQ(r.composed(k), r.background[k]);
    }
}

TEST(ReferenceFog, ViewRaysFollowTheCamera)
{
    ReferenceView v;
    v.eye = {1.0, 2.0, 3.0};
    v.target = {101.0, 2.0, 3.0};
    v.fov_y_deg = 90.0;
    v.width = 3;
    v.height = 3;
    EXPECT_NEAR(glm::length(v.ray(1, 1) - glm::dvec3(1, 0, 0)), 0.0, 1e-15);
    // Row 0 is the top: the ray through the top row's centre points up by atan(2/3 tan 45).
    const glm::dvec3 top = v.ray(1, 0);
    EXPECT_GT(top.z, 0.0);
    EXPECT_NEAR(std::atan2(top.z, top.x), std::atan(2.0 / 3.0), 1e-12);
    const glm::dvec3 left = v.ray(0, 1);
    EXPECT_GT(left.y, 0.0);  // x forward, z up: left is +y
}

TEST(ReferenceFog, NoSkyAndBlackGroundLeaveTheSunsLightAlone)
{
    // FogLighting::sky false: no ambient in the fog and a black sky (no horizon, no glow);
    // ReferenceOptions::shade_terrain false: the ground is black but still ends the ray.
    const double sigma = 0.01, a = 0.9, g = 0.5, H = 100.0, z = 50.0, d = 200.0, e = 0.5;
    const Medium m = slab(0.0, H, sigma, 1.0, a, g);
    FogLighting light;
    light.sun_direction = {std::cos(e), 0.0, std::sin(e)};
    light.sun_radiance = {3.0, 2.0, 1.0};
    light.ambient = {0.2, 0.3, 0.4};
    light.terrain_shadows = false;
    light.sky = false;
    const glm::dvec3 w(0.0, 1.0, 0.0);
    const RayFog r = reference_ray({&m, {}}, nullptr, {0.0, 0.0, z}, w, d, light);
    const glm::dvec3 expected = a * std::numbers::pi * light.sun_radiance * std::exp(-sigma * (H - z) / std::sin(e)) *
        henyey_greenstein(glm::dot(w, light.sun_direction), g) * (1.0 - std::exp(-sigma * d));
    expect_rel(r.inscatter, expected, 1e-9);
    EXPECT_EQ(r.surface, glm::dvec3(0.0));
    const RayFog sky = reference_ray({}, nullptr, {0.0, 0.0, z}, light.sun_direction, 1e6, light);
    EXPECT_EQ(sky.surface, glm::dvec3(0.0));  // looking into the sun: no glow either
    light.sky = true;
    EXPECT_GT(reference_ray({}, nullptr, {0.0, 0.0, z}, light.sun_direction, 1e6, light).surface.x, 0.5);

    const Heightfield ground = flat();
    ReferenceOptions black;
    black.shade_terrain = false;
    const RayFog lit = reference_ray({}, &ground, {0.0, 0.0, 300.0}, {0.0, 0.0, -1.0}, 1e6, light);
    const RayFog dark = reference_ray({}, &ground, {0.0, 0.0, 300.0}, {0.0, 0.0, -1.0}, 1e6, light, black);
    ASSERT_TRUE(lit.hit_terrain && dark.hit_terrain);
    EXPECT_GT(lit.surface.y, 0.1);
    EXPECT_EQ(dark.surface, glm::dvec3(0.0));
    EXPECT_EQ(dark.distance, lit.distance);
}

TEST(ReferenceFog, TheGridsEdgeIsNoWall)
{
    // A plate at 100 m over [-500, 500]^2, bare (no surround): the terrain is a surface, as the
    // GL terrain and the shadow map draw it, so a ray from outside passing under its edge sees no
    // wall.
    Heightfield plate;
    plate.nx = plate.ny = 11;
    plate.dx = plate.dy = 100.0;
    plate.x0 = plate.y0 = -500.0;
    plate.z.assign(121, 100.0);
    plate.valid.assign(121, 1);
    ReferenceOptions bare;
    bare.surround = false;
    ReferenceView view;
    view.width = view.height = 1;
    view.fov_y_deg = 10.0;
    view.eye = {-2000.0, 0.0, 50.0};
    view.target = {0.0, 0.0, 50.0};
    EXPECT_TRUE(std::isinf(render_reference_fog({}, &plate, view, FogLighting{}, bare).depth[0]));
    // From above, the same plate is hit where it is: 2000 m away, 500 m down.
    view.eye = {-2000.0, 0.0, 600.0};
    view.target = {0.0, 0.0, 100.0};
    EXPECT_NEAR(render_reference_fog({}, &plate, view, FogLighting{}, bare).depth[0], std::hypot(2000.0, 500.0), 1e-6);
}

TEST(ReferenceFog, RaysBeyondTheGridMeetItsSurround)
{
    // z = 1000 + 0.3 y over [-500, 500]^2: its surround (ground.hpp) is 1000 m from 250 m out.
    Heightfield hf;
    hf.nx = hf.ny = 11;
    hf.dx = hf.dy = 100.0;
    hf.x0 = hf.y0 = -500.0;
    for (int j = 0; j < 11; ++j)
        for (int i = 0; i < 11; ++i)
            hf.z.push_back(1000.0 + 0.3 * hf.y_of(j));
    hf.valid.assign(121, 1);
    const Ground ground(hf);
    FogLighting light;
    // Down onto the flat ground 1500 m beyond the edge: the plane, exactly.
    RayFog r =
        reference_ray({}, &hf, {-3000.0, 0.0, 1500.0}, glm::normalize(glm::dvec3(1000.0, 0.0, -500.0)), 1e6, light);
    ASSERT_TRUE(r.hit_terrain);
    EXPECT_NEAR(r.distance, std::hypot(1000.0, 500.0), 1e-9);
    // Straight down into the eased band, 125 m west of the edge at y = 100: the closed form.
    r = reference_ray({}, &hf, {-625.0, 100.0, 2000.0}, {0.0, 0.0, -1.0}, 1e6, light);
    ASSERT_TRUE(r.hit_terrain);
    EXPECT_NEAR(2000.0 - r.distance, 1000.0 + 30.0 * 0.5, 1e-9);
    // Oblique rays through the band: each ends on the ground, and above it before.
    for (double azimuth = 0.0; azimuth < 6.28; azimuth += 0.37) {
        const glm::dvec3 o(-700.0 * std::cos(azimuth), -700.0 * std::sin(azimuth), 1300.0);
        const glm::dvec3 w = glm::normalize(glm::dvec3(std::cos(azimuth + 0.4), std::sin(azimuth + 0.4), -0.35));
        r = reference_ray({}, &hf, o, w, 1e6, light);
        ASSERT_TRUE(r.hit_terrain) << azimuth;
        const glm::dvec3 p = o + w * r.distance;
        EXPECT_NEAR(p.z, ground.height(p.x, p.y), 1e-6) << azimuth;
        for (double t = 0.0; t < r.distance - 1.0; t += 5.0) {
            const glm::dvec3 q = o + w * t;
            ASSERT_GT(q.z, ground.height(q.x, q.y)) << azimuth << " " << t;
        }
    }
    // Without the surround the same rays leave the bare tile.
    ReferenceOptions bare;
    bare.surround = false;
    EXPECT_FALSE(reference_ray({}, &hf, {-3000.0, 0.0, 1500.0}, glm::normalize(glm::dvec3(1000.0, 0.0, -500.0)), 1e6,
                               light, bare)
                     .hit_terrain);
}
