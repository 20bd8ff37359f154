// The light-transport volume (light_volume.hpp) and its bake (light_volume_bake.hpp) against
// closed forms and the path tracer as the oracle: the spherical harmonics' orthonormality and the
// Funk-Hecke identity of Henyey-Greenstein (g^l), the convolution of two Henyey-Greenstein lobes
// (a lobe of g1 g2), the baked multiple scattering of a uniform slab against the path tracer at
// points and directions, a height fog inside a thin Medium (the bake's first scatterings drawn in
// the height fog, above a thin Medium's top and under a lifted Medium's floor) against the path
// tracer, no diffuse light without scattering, diffuse light in
// the terrain's shadow beside sunlit fog, the cells of a wall the sun shines into no noisier than
// the interior's, determinism across threads (a slab; terrain, height fog and photons per patch
// by the light its rays scatter), bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <numbers>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "fog_test_terrains.hpp"
#include "kiri/geometry/medium/light_volume.hpp"
#include "kiri/geometry/medium/medium.hpp"
#include "kiri/geometry/reference/light_volume_bake.hpp"
#include "kiri/geometry/reference/path_tracer.hpp"
#include "kiri/geometry/reference/reference_fog.hpp"
#include "slab_medium.hpp"

using namespace kiri::geometry;

namespace {

constexpr int max_q = light_volume_max_bands * light_volume_max_bands;

// A uniform slab of fog between z = bottom and z = top over [-half, half]^2 (or x in [x0, x0 + 2 half]).
Medium slab(double bottom, double top, double sigma, double albedo, double g, double half, double x0 = std::nan(""))
{
    return kiri::test::slab_medium(bottom, top, sigma, albedo, g, half, std::isnan(x0) ? -half : x0);
}

glm::dvec3 sun_towards(double elevation, double azimuth)
{
    return {std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth), std::sin(elevation)};
}

using kiri::test::gauss_legendre;

// A volume of one cell holding the moments `m`.
LightVolume one_cell(const std::array<double, max_q>& m, int bands)
{
    LightVolume v;
    v.nx = v.ny = v.nz = 1;
    v.bands = bands;
    v.x0 = v.y0 = -1.0;
    v.dx = v.dy = 2.0;
    v.moments.assign(m.begin(), m.begin() + bands * bands);
    return v;
}

LightVolumeOptions small_bake(long long photons)
{
    LightVolumeOptions o;
    o.photons = photons;
    o.max_side = 4;
    o.threads = 2;
    return o;
}

}  // namespace

TEST(LightVolume, SphericalHarmonicsAreOrthonormal)
{
    const int bands = light_volume_max_bands, n = bands * bands;
    // Exact for polynomials of degree 2 (bands - 1) in cos(theta) and in the azimuth's harmonics.
    std::vector<double> gram(std::size_t(n) * n, 0.0);
    const int n_phi = 32;
    for (const auto& [c, w] : gauss_legendre(16))
        for (int j = 0; j < n_phi; ++j) {
            const double phi = 2.0 * std::numbers::pi * (j + 0.5) / n_phi, r = std::sqrt(1.0 - c * c);
            std::array<double, max_q> y{};
            real_spherical_harmonics({r * std::cos(phi), r * std::sin(phi), c}, bands, y.data());
            for (int a = 0; a < n; ++a)
                for (int b = 0; b < n; ++b)
                    gram[std::size_t(a) * n + b] += w * 2.0 * std::numbers::pi / n_phi * y[a] * y[b];
        }
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b)
            EXPECT_NEAR(gram[std::size_t(a) * n + b], a == b ? 1.0 : 0.0, 1e-12) << a << ", " << b;
    // Y_00 and Y_1m in closed form.
    std::array<double, max_q> y{};
    const glm::dvec3 d = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
    real_spherical_harmonics(d, 2, y.data());
    EXPECT_NEAR(y[0], 0.5 / std::sqrt(std::numbers::pi), 1e-15);
    const double k1 = std::sqrt(3.0 / (4.0 * std::numbers::pi));
    EXPECT_NEAR(y[1], k1 * d.y, 1e-14);
    EXPECT_NEAR(y[2], k1 * d.z, 1e-14);
    EXPECT_NEAR(y[3], k1 * d.x, 1e-14);
}

TEST(LightVolume, HenyeyGreensteinConvolvesEachBandByGToTheL)
{
    // Funk-Hecke: integral p_HG(d . o, g) Y_lm(d) dd = g^l Y_lm(o), the identity in_scattered
    // rests on; phase_weights gives g^l Y_lm(o).
    const double g = 0.7;
    const glm::dvec3 o = glm::normalize(glm::dvec3(-0.2, 0.6, 0.4));
    const int bands = light_volume_max_bands;
    LightVolume v = one_cell({}, bands);
    std::array<double, max_q> weights{}, y_o{};
    v.phase_weights(o, g, weights.data());
    real_spherical_harmonics(o, bands, y_o.data());
    std::array<double, max_q> integral{};
    const int n_phi = 128;
    for (const auto& [c, w] : gauss_legendre(64))
        for (int j = 0; j < n_phi; ++j) {
            const double phi = 2.0 * std::numbers::pi * (j + 0.5) / n_phi, r = std::sqrt(1.0 - c * c);
            const glm::dvec3 d(r * std::cos(phi), r * std::sin(phi), c);
            std::array<double, max_q> y{};
            real_spherical_harmonics(d, bands, y.data());
            const double p = w * 2.0 * std::numbers::pi / n_phi * henyey_greenstein(glm::dot(d, o), g);
            for (int q = 0; q < bands * bands; ++q)
                integral[q] += p * y[q];
        }
    for (int l = 0; l < bands; ++l)
        for (int q = l * l; q < (l + 1) * (l + 1); ++q) {
            EXPECT_NEAR(integral[q], std::pow(g, l) * y_o[q], 1e-6) << "l " << l << ", q " << q;
            EXPECT_NEAR(weights[q], std::pow(g, l) * y_o[q], 1e-14);
        }
}

TEST(LightVolume, TwoHenyeyGreensteinLobesConvolveToOneOfTheProduct)
{
    // Diffuse radiance of a Henyey-Greenstein lobe of g2 about a: its moments are g2^l Y_lm(a), and
    // the light a phase function of g scatters towards o is p_HG(o . a, g g2) (the product of the
    // Legendre coefficients), here truncated to the bands stored: sum_{l < 8} (2l + 1) / (4 pi)
    // (g g2)^l P_l(o . a), within the tail's bound of the whole lobe.
    const double g = 0.8, g2 = 0.5, gg = g * g2;
    const int bands = light_volume_max_bands;
    const glm::dvec3 a = glm::normalize(glm::dvec3(0.5, 0.2, -0.8));
    std::array<double, max_q> m{};
    real_spherical_harmonics(a, bands, m.data());
    for (int l = 0; l < bands; ++l)
        for (int q = l * l; q < (l + 1) * (l + 1); ++q)
            m[q] *= std::pow(g2, l);
    const LightVolume v = one_cell(m, bands);
    double tail = 0.0;
    for (int l = bands; l < 200; ++l)
        tail += (2.0 * l + 1.0) / (4.0 * std::numbers::pi) * std::pow(gg, l);
    for (const glm::dvec3& o : {a, -a, glm::normalize(glm::dvec3(0.0, 1.0, 0.3)), glm::dvec3(0.0, 0.0, 1.0)}) {
        const double x = glm::dot(o, a);
        double p0 = 1.0, p1 = x, series = (1.0 + 3.0 * gg * x) / (4.0 * std::numbers::pi);
        for (int l = 2; l < bands; ++l) {
            const double p2 = ((2.0 * l - 1.0) * x * p1 - (l - 1.0) * p0) / l;
            p0 = p1;
            p1 = p2;
            series += (2.0 * l + 1.0) / (4.0 * std::numbers::pi) * std::pow(gg, l) * p2;
        }
        EXPECT_NEAR(v.in_scattered(0.0, 0.0, 0.5, o, g), series, 1e-12);
        EXPECT_NEAR(series, henyey_greenstein(x, gg), tail);
    }
}

TEST(LightVolume, BakedSlabAgreesWithThePathTracer)
{
    // A uniform slab 100 m thick (sigma 0.02, albedo 0.99, g 0.8) on a black ground under the sun
    // 35 degrees up: single scattering plus the baked volume (the CPU reference's `baked`) against
    // every order of scattering path traced, at a point above looking down, inside looking along
    // and towards the sun. The bound is 10 % (the goal of the lighting model) plus the noise.
    const Heightfield ground =
        kiri::test::make_heightfield(11, 11, 400.0, -2000.0, -2000.0, [](double, double) { return 0.0; });
    const Medium m = slab(0.0, 100.0, 0.02, 0.99, 0.8, 2000.0);
    FogLighting light;
    light.sun_direction = sun_towards(35.0 * std::numbers::pi / 180.0, 0.4);
    light.sun_radiance = glm::dvec3(1.0);
    light.sky = false;
    light.terrain_shadows = true;
    light.multiple_scattering = MultipleScattering::baked;
    light.light_volume = std::make_shared<const LightVolume>(
        bake_light_volume({&m, {}}, &ground, light.sun_direction, small_bake(60000)));
    ASSERT_FALSE(light.light_volume->empty());
    ReferenceOptions ro;
    ro.shade_terrain = false;
    PathTracerOptions po;
    po.samples = 6000;
    po.sky = PathSky::none;
    po.ground = PathGround::black;
    const glm::dvec3 s = light.sun_direction;
    const std::pair<glm::dvec3, glm::dvec3> rays[] = {{{0.0, 0.0, 300.0}, glm::normalize(glm::dvec3(0.3, -0.2, -1.0))},
                                                      {{0.0, 0.0, 50.0}, glm::normalize(glm::dvec3(-s.y, s.x, 0.0))},
                                                      {{0.0, 0.0, 50.0}, s}};
    for (const auto& [origin, dir] : rays) {
        const RayFog model = reference_ray({&m, {}}, &ground, origin, dir, 1e6, light, ro);
        FogLighting single = light;
        single.multiple_scattering = MultipleScattering::none;
        const RayFog once = reference_ray({&m, {}}, &ground, origin, dir, 1e6, single, ro);
        const PathEstimate truth = path_traced_ray({&m, {}}, &ground, origin, dir, 1e6, light, po, 7);
        EXPECT_NEAR(model.inscatter.x, truth.radiance.x, 0.10 * truth.radiance.x + 3.0 * truth.std_error.x)
            << "from " << origin.z << " along " << dir.x << ", " << dir.y << ", " << dir.z;
        // Most of this light is scattered more than once.
        EXPECT_GT(model.inscatter.x, 1.3 * once.inscatter.x);
    }
}

TEST(LightVolume, NoScatteringNoDiffuseLight)
{
    const Medium black = slab(0.0, 100.0, 0.02, 0.0, 0.8, 1000.0);
    const LightVolume v = bake_light_volume({&black, {}}, nullptr, sun_towards(0.6, 0.3), small_bake(5000));
    ASSERT_FALSE(v.empty());
    for (double m : v.moments)
        EXPECT_EQ(m, 0.0);
    EXPECT_EQ(v.in_scattered(0.0, 0.0, 0.5, glm::dvec3(0.0, 0.0, 1.0), 0.8), 0.0);
    // With scattering the same slab holds diffuse light everywhere inside.
    const Medium white = slab(0.0, 100.0, 0.02, 0.99, 0.8, 1000.0);
    const LightVolume w = bake_light_volume({&white, {}}, nullptr, sun_towards(0.6, 0.3), small_bake(5000));
    for (double h : {0.05, 0.5, 0.95})
        EXPECT_GT(w.in_scattered(0.0, 0.0, h, glm::dvec3(0.0, 0.0, 1.0), 0.0), 0.01);
}

TEST(LightVolume, TheTerrainsShadowHoldsDiffuseLightFromTheSunlitFog)
{
    // A ridge 400 m high at x = -500, west of a slab of fog over x in [0, 1000], under a western sun
    // 20 degrees up: its shadow covers the fog up to x = 324 and, below the line
    // z = 400 - (x + 500) tan 20, the fog's lower part up to x = 599. At (480, 10) the fog lies in
    // the shadow with sunlit fog above it, whose light scattered downward still reaches it: less
    // than in the sun at the same height, far more than nothing; and the CPU reference sees it
    // there, where single scattering alone is black.
    const Heightfield ground = kiri::test::make_heightfield(
        61, 21, 50.0, -1000.0, -500.0, [](double x, double) { return std::abs(x + 500.0) < 30.0 ? 400.0 : 0.0; });
    const Medium m = slab(0.0, 100.0, 0.02, 0.99, 0.8, 500.0, 0.0);
    const glm::dvec3 sun = sun_towards(20.0 * std::numbers::pi / 180.0, std::numbers::pi);  // from the west
    LightVolumeOptions o = small_bake(60000);
    o.cell_size = 50.0;
    o.max_side = 40;
    const LightVolume v = bake_light_volume({&m, {}}, &ground, sun, o);
    // The light at a point 10 m up (h 0.1), each on its side of the shadow (in_scattered_at, as the
    // renderers take it).
    ASSERT_TRUE(v.has_shadow_parts());
    std::array<double, max_q> isotropic{};
    v.phase_weights({0.0, 0.0, 1.0}, 0.0, isotropic.data());
    const auto at = [&](double x) { return v.in_scattered_at(x, 0.0, 10.0, 0.1, isotropic.data()); };
    const double shadow = at(480.0), sunlit = at(900.0);
    const double deep = at(75.0);  // under 200 m of shadow
    EXPECT_LT(v.shadow_top_at(900.0, 0.0), 10.0);
    EXPECT_GT(v.shadow_top_at(480.0, 0.0), 10.0);
    EXPECT_GT(shadow, 0.2 * sunlit);
    EXPECT_LT(shadow, 0.8 * sunlit);
    EXPECT_LT(deep, 0.5 * shadow);

    FogLighting light;
    light.sun_direction = sun;
    light.sun_radiance = glm::dvec3(1.0);
    light.sky = false;
    light.terrain_shadows = true;
    light.multiple_scattering = MultipleScattering::none;
    ReferenceOptions ro;
    ro.shade_terrain = false;
    const glm::dvec3 origin(480.0, -100.0, 10.0), along(0.0, 1.0, 0.0);
    const RayFog single = reference_ray({&m, {}}, &ground, origin, along, 200.0, light, ro);
    light.multiple_scattering = MultipleScattering::baked;
    light.light_volume = std::make_shared<const LightVolume>(v);
    const RayFog baked = reference_ray({&m, {}}, &ground, origin, along, 200.0, light, ro);
    EXPECT_EQ(single.inscatter.x, 0.0);
    // The fog along the ray is uniform: the integral of sigma albedo J(t) exp(-sigma t) over its
    // 200 m, J the diffuse light the volume scatters towards the eye (the midpoint rule, 1 m).
    // The slab's columns are alike: one column_scale for them all.
    const double scale = v.column_scale(m.column(480.0, 0.0));
    EXPECT_NEAR(scale, -std::expm1(-0.02 * 100.0), 1e-12);
    std::array<double, max_q> towards_eye{};
    v.phase_weights(-along, 0.8, towards_eye.data());
    double expected = 0.0;
    for (double t = 0.5; t < 200.0; t += 1.0)
        expected += 0.02 * 0.99 * v.in_scattered_at(480.0, -100.0 + t, 10.0, 0.1, towards_eye.data(), scale) *
            std::exp(-0.02 * t);
    EXPECT_GT(expected, 0.2 * 0.99 * shadow);
    EXPECT_NEAR(baked.inscatter.x, expected, 0.01 * expected);
}

TEST(LightVolume, BakeIsDeterministicOnAnyNumberOfThreads)
{
    const Medium m = slab(0.0, 60.0, 0.03, 0.95, 0.7, 1000.0);
    LightVolumeOptions o = small_bake(3000);
    o.threads = 1;
    const LightVolume one = bake_light_volume({&m, {}}, nullptr, sun_towards(0.5, 1.0), o);
    o.threads = 3;
    const LightVolume three = bake_light_volume({&m, {}}, nullptr, sun_towards(0.5, 1.0), o);
    ASSERT_FALSE(one.empty());
    EXPECT_EQ(one.moments, three.moments);
    EXPECT_EQ(one.deposits, three.deposits);
    o.seed = 2;
    EXPECT_NE(bake_light_volume({&m, {}}, nullptr, sun_towards(0.5, 1.0), o).moments, one.moments);
}

TEST(LightVolume, BakeOverTerrainWithHeightFogIsDeterministicOnAnyNumberOfThreads)
{
    // Every part of the bake: a ridge that hides and absorbs, a height fog, photons per patch of
    // the box's faces by the share of the sunlight its rays scatter (photons = 0).
    const Heightfield ground = kiri::test::make_heightfield(
        21, 21, 100.0, -1000.0, -1000.0, [](double x, double) { return std::abs(x) < 100.0 ? 150.0 : 0.0; });
    const Medium m = slab(0.0, 80.0, 0.01, 0.95, 0.7, 1000.0);
    HeightFog haze;
    haze.extinction = 0.02;
    haze.base = 20.0;
    haze.scale_height = 20.0;
    LightVolumeOptions o;
    o.photons_per_column = 40;
    o.cell_size = 250.0;
    o.max_side = 8;
    o.min_photons = 0;
    o.threads = 1;
    const glm::dvec3 sun = sun_towards(0.4, 2.8);
    const LightVolume one = bake_light_volume({&m, haze}, &ground, sun, o);
    o.threads = 3;
    const LightVolume three = bake_light_volume({&m, haze}, &ground, sun, o);
    ASSERT_FALSE(one.empty());
    EXPECT_GT(one.photons, 8 * 8 * 10);  // at least a quarter of 40 per column
    // At most 40 per column on the top and as many per area seen from the sun on the two side
    // faces it shines on (the box 180 m deep: up to the height fog's top).
    const double sides = 8 * 250.0 * 180.0 * (std::abs(sun.x) + std::abs(sun.y)) / (250.0 * 250.0 * sun.z);
    EXPECT_LE(double(one.photons), (8 * 8 + sides) * 40 + 16);
    EXPECT_EQ(one.moments, three.moments);
    EXPECT_EQ(one.deposits, three.deposits);
    // A floor on the photons in all raises every column's count by one whole factor.
    o.min_photons = 20 * one.photons;
    const LightVolume floored = bake_light_volume({&m, haze}, &ground, sun, o);
    EXPECT_GE(floored.photons, 20 * one.photons);
    EXPECT_LE(floored.photons, 21 * one.photons);
}

TEST(LightVolume, BadInputStaysFinite)
{
    const glm::dvec3 sun = sun_towards(0.5, 0.0);
    const Medium clear = slab(0.0, 100.0, 0.0, 0.99, 0.8, 1000.0);
    EXPECT_TRUE(bake_light_volume({&clear, {}}, nullptr, sun, small_bake(100)).empty());
    const Medium m = slab(0.0, 100.0, 0.02, 0.99, 0.8, 1000.0);
    EXPECT_TRUE(bake_light_volume({&m, {}}, nullptr, sun_towards(-0.2, 0.0), small_bake(100)).empty());
    EXPECT_TRUE(bake_light_volume({&m, {}}, nullptr, glm::dvec3(0.0), small_bake(100)).empty());
    EXPECT_TRUE(bake_light_volume({&m, {}}, nullptr, glm::dvec3(std::nan("")), small_bake(100)).empty());
    EXPECT_TRUE(bake_light_volume({nullptr, {}}, nullptr, sun, small_bake(100)).empty());
    // Impossible sizes are bounded: at most 2^23 sums.
    LightVolumeOptions huge = small_bake(100);
    huge.max_side = 1 << 30;
    huge.levels = 1 << 20;
    huge.bands = 99;
    huge.cell_size = 1e-9;
    const LightVolume bounded = bake_light_volume({&m, {}}, nullptr, sun, huge);
    EXPECT_EQ(bounded.nz, 64);
    EXPECT_EQ(bounded.bands, light_volume_max_bands);
    EXPECT_LE(double(bounded.nx) * bounded.ny * bounded.nz * bounded.bands * bounded.bands, double(1 << 23));
    EXPECT_GE(bounded.nx, 8);
    const LightVolume v = bake_light_volume({&m, {}}, nullptr, sun, small_bake(2000));
    const double nan = std::nan("");
    for (const double x : {nan, 0.0, 1e30})
        for (const double g : {nan, -1.0, 1.0, 0.8}) {
            const double d = v.in_scattered(x, x, x, glm::dvec3(x, 0.0, 1.0), g);
            EXPECT_TRUE(std::isfinite(d) && d >= 0.0) << x << ", " << g;
        }
    const LightVolume empty;
    EXPECT_EQ(empty.in_scattered(0.0, 0.0, 0.5, glm::dvec3(0.0, 0.0, 1.0), 0.8), 0.0);
    // `baked` without a volume is single scattering.
    FogLighting light;
    light.sky = false;
    light.multiple_scattering = MultipleScattering::baked;
    const RayFog without = reference_ray({&m, {}}, nullptr, {0.0, 0.0, 50.0}, {1.0, 0.0, 0.0}, 500.0, light);
    light.multiple_scattering = MultipleScattering::none;
    const RayFog single = reference_ray({&m, {}}, nullptr, {0.0, 0.0, 50.0}, {1.0, 0.0, 0.0}, 500.0, light);
    EXPECT_EQ(without.inscatter, single.inscatter);
}

namespace {

// A height fog (sigma 0.03 up to its base at 30 m, falling off over 25 m above) in or over a thin
// Medium (sigma 0.002) `top` metres deep over a flat black ground, the sun 30 degrees up: single
// scattering plus the baked volume against every order path traced, looking down into it from
// 400 m and level through it from `level_z`; each within 10 % (plus 3 standard errors) and at
// least 1.3 times the single scattering. Returns the light volume.
std::shared_ptr<const LightVolume> expect_baked_height_fog_agrees(double top, double level_z, double bottom = 0.0)
{
    const Heightfield ground =
        kiri::test::make_heightfield(11, 11, 400.0, -2000.0, -2000.0, [](double, double) { return 0.0; });
    const Medium m = slab(bottom, top, 0.002, 0.99, 0.8, 2000.0);
    HeightFog haze;
    haze.extinction = 0.03;
    haze.base = 30.0;
    haze.scale_height = 25.0;
    haze.albedo = 0.99;
    haze.anisotropy = 0.6;
    FogLighting light;
    light.sun_direction = sun_towards(30.0 * std::numbers::pi / 180.0, 0.7);
    light.sun_radiance = glm::dvec3(1.0);
    light.sky = false;
    light.multiple_scattering = MultipleScattering::baked;
    light.light_volume = std::make_shared<const LightVolume>(
        bake_light_volume({&m, haze}, &ground, light.sun_direction, small_bake(40000)));
    EXPECT_FALSE(light.light_volume->empty());
    ReferenceOptions ro;
    ro.shade_terrain = false;
    PathTracerOptions po;
    po.samples = 3000;
    po.sky = PathSky::none;
    po.ground = PathGround::black;
    const std::pair<glm::dvec3, glm::dvec3> rays[] = {
        {{0.0, 0.0, 400.0}, glm::normalize(glm::dvec3(0.2, 0.1, -1.0))},
        {{0.0, 0.0, level_z}, glm::normalize(glm::dvec3(1.0, -0.3, 0.0))}};
    for (const auto& [origin, dir] : rays) {
        const RayFog model = reference_ray({&m, haze}, &ground, origin, dir, 1e6, light, ro);
        FogLighting single = light;
        single.multiple_scattering = MultipleScattering::none;
        const RayFog once = reference_ray({&m, haze}, &ground, origin, dir, 1e6, single, ro);
        const PathEstimate truth = path_traced_ray({&m, haze}, &ground, origin, dir, 1e6, light, po, 5);
        std::printf(
            "    Medium %.0f m deep, from %.0f m: baked %.5f (single scattering %.5f), path traced %.5f +- "
            "%.5f\n",
            top - bottom, origin.z, model.inscatter.x, once.inscatter.x, truth.radiance.x, truth.std_error.x);
        EXPECT_NEAR(model.inscatter.x, truth.radiance.x, 0.10 * truth.radiance.x + 3.0 * truth.std_error.x)
            << "from " << origin.z;
        EXPECT_GT(model.inscatter.x, 1.3 * once.inscatter.x);
    }
    return light.light_volume;
}

}  // namespace

TEST(LightVolume, BakedHeightFogUnderAThinMediumAgreesWithThePathTracer)
{
    // Inside a Medium 200 m deep: most of the light scatters first in the height fog, whose first
    // scatterings the bake draws along the sun in closed form.
    expect_baked_height_fog_agrees(200.0, 20.0);
}

TEST(LightVolume, BakedHeightFogAboveAThinMediumsTopAgreesWithThePathTracer)
{
    // The same height fog over a Medium only 15 m deep: nearly all of the height fog lies above
    // the Medium's top. The bake followed its photons only within the Medium's box and the cells
    // held the Medium's shell alone, so the model drew the height fog's single scattering there
    // and nothing more (looking down into it 0.024 against the path tracer's 0.133, level through
    // it 0.083 against 0.402). The photons go up to the height fog's top now, and the cells'
    // columns with them (LightVolume::shell).
    const auto volume = expect_baked_height_fog_agrees(15.0, 40.0);
    EXPECT_DOUBLE_EQ(volume->haze_top, 30.0 + 8.0 * 25.0);
    EXPECT_DOUBLE_EQ(volume->shell(slab(0.0, 15.0, 0.002, 0.99, 0.8, 2000.0).column(0.0, 0.0), 0.0, 0.0).top, 230.0);
}

TEST(LightVolume, BakedHeightFogUnderALiftedMediumsFloorAgreesWithThePathTracer)
{
    // A blanket from 80 to 120 m over a height fog that fills the ground's first 30 m and thins
    // above: the default scene's valleys, where the blanket lies a set depth under its top and
    // the haze fills the valley under it. The cells' columns began at the Medium's floor, so the
    // haze under it had its single scattering alone (in the default scene's view from above, 42 %
    // of the haze the eye saw; the view 0.90 of the path tracer's brightness). They reach down to
    // the ground now where the height fog lies under the floor (LightVolume::floors).
    const auto volume = expect_baked_height_fog_agrees(120.0, 20.0, 80.0);
    ASSERT_EQ(volume->floors.size(), std::size_t(volume->floor_nx) * volume->floor_ny);
    // Two samples a DEM spacing (400 m), four to sixteen a cell; the terrain's shadow's tops on
    // the same grid.
    const int per_cell = std::clamp(int(std::ceil(2.0 * std::max(volume->dx, volume->dy) / 400.0)), 4, 16);
    EXPECT_EQ(volume->floor_nx, per_cell * volume->nx + 1);
    EXPECT_EQ(volume->shadow_nx, volume->floor_nx);
    EXPECT_EQ(volume->shadow_ny, volume->floor_ny);
    EXPECT_DOUBLE_EQ(volume->floor_at(100.0, -300.0), 0.0);
    EXPECT_DOUBLE_EQ(volume->shell(slab(80.0, 120.0, 0.002, 0.99, 0.8, 2000.0).column(0.0, 0.0), 0.0, 0.0).floor, 0.0);
}

TEST(LightVolume, ALitWallsCellsAreNoNoisierThanTheInteriors)
{
    // A slab 2.5 km wide under a sun 10 degrees up from the west: most of the sunlight the cells
    // along its west wall scatter enters through the wall and scatters within a mean free path
    // (50 m) of it, in cells 156 m across. Drawn along rays of sunlight, the first scatterings
    // lie where that light goes in; drawn in columns (the bake before), a few photons of large
    // weight landed in the wall's skin and those cells' moments were twice as noisy as the
    // interior's (relative standard deviation of L_00 over four seeds: 23 % against 11 % on a
    // slab 10 km wide). Both estimators have the same mean: the cells of four seeds' bakes
    // average within a few per cent of each other wherever they are.
    const Heightfield ground =
        kiri::test::make_heightfield(11, 11, 250.0, -1250.0, -1250.0, [](double, double) { return 0.0; });
    const Medium m = slab(0.0, 100.0, 0.02, 0.99, 0.8, 1250.0);
    const double elevation = 10.0 * std::numbers::pi / 180.0;
    const glm::dvec3 sun = sun_towards(elevation, std::numbers::pi);  // from -x
    std::vector<LightVolume> bakes;
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
        LightVolumeOptions o;
        o.seed = seed;
        o.cell_size = 2500.0 / 16;
        o.min_photons = 0;
        o.threads = 2;
        bakes.push_back(bake_light_volume({&m, {}}, &ground, sun, o));
        ASSERT_EQ(bakes.back().nx, 16);
    }
    const LightVolume& v = bakes.front();
    const int nc = v.bands * v.bands;
    // The mean over the cells picked of L_00's relative standard deviation over the seeds, and of its mean.
    const auto noise = [&](auto picked) {
        double relative = 0.0, mean_of_means = 0.0;
        int cells = 0;
        for (int k = 0; k < v.nz; ++k)
            for (int j = 2; j < v.ny - 2; ++j)
                for (int i = 0; i < v.nx; ++i) {
                    if (!picked(i))
                        continue;
                    const std::size_t c = ((std::size_t(k) * v.ny + j) * v.nx + i) * nc;
                    double s1 = 0.0, s2 = 0.0;
                    for (const LightVolume& b : bakes) {
                        s1 += b.moments[c];
                        s2 += b.moments[c] * b.moments[c];
                    }
                    const double n = double(bakes.size()), mean = s1 / n;
                    const double variance = std::max(s2 / n - mean * mean, 0.0) * n / (n - 1.0);
                    EXPECT_GT(mean, 0.0);
                    relative += std::sqrt(variance) / mean;
                    mean_of_means += mean;
                    ++cells;
                }
        return std::pair(relative / cells, mean_of_means / cells);
    };
    const auto [wall, wall_light] = noise([](int i) { return i == 0; });
    const auto [interior, interior_light] = noise([&](int i) { return i >= 4 && i < v.nx - 4; });
    std::printf("L_00 relative standard deviation: wall %.2f %%, interior %.2f %%; mean L_00 %.4f and %.4f\n",
                100.0 * wall, 100.0 * interior, wall_light, interior_light);
    EXPECT_LT(wall, interior);
    // The wall's cells hold more light than the interior's: the sunlight comes in there too.
    EXPECT_GT(wall_light, 1.5 * interior_light);
}
