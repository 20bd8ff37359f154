// The air between the eye and what it sees (air_light.hpp): its haze in closed form, the scene's
// air, and the CPU reference seeing the fog and the ground through it as the renderers do:
// against the exact transfer through the air and a uniform slab together.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "fog_test_terrains.hpp"
#include "kiri/geometry/medium/air_light.hpp"
#include "kiri/geometry/reference/reference_fog.hpp"
#include "slab_medium.hpp"

using namespace kiri::geometry;

using kiri::test::expect_rel;
using kiri::test::sky_only;

TEST(AirLight, HazeAndSeenInClosedForm)
{
    const AirLight air{1.0 / 150000.0, {0.9, 1.0, 1.1}};
    EXPECT_EQ(air.haze(0.0), 0.0);
    EXPECT_NEAR(air.haze(42000.0), 1.0 - std::exp(-0.28), 1e-15);
    const glm::dvec3 l(0.2, 0.4, 0.6);
    const double h = 1.0 - std::exp(-0.1);
    expect_rel(air.seen(l, 15000.0), l * (1.0 - h) + air.radiance * h, 1e-14);
    // No air: what is seen is what is there, at any distance.
    expect_rel(AirLight{}.seen(l, 1e9), l, 0.0);
    // Finite for any input: an infinite distance is all air, NaN none.
    EXPECT_EQ(air.haze(std::numeric_limits<double>::infinity()), 1.0);
    EXPECT_EQ(air.haze(std::nan("")), 0.0);
    EXPECT_EQ(air.haze(-5.0), 0.0);
}

TEST(AirLight, SceneAirGrowsWithTheTerrainAndVanishesInABlackWorld)
{
    const glm::dvec3 ambient(0.22, 0.28, 0.38);
    const AirLight small = scene_air(20000.0, ambient);
    EXPECT_DOUBLE_EQ(small.extinction, 1.0 / 150000.0);                         // up to 50 km across: 150 km
    EXPECT_DOUBLE_EQ(scene_air(200000.0, ambient).extinction, 1.0 / 600000.0);  // 3 x across
    EXPECT_DOUBLE_EQ(scene_air(std::nan(""), ambient).extinction, 1.0 / 150000.0);
    // The horizon's colour of sky.frag: mix(3 ambient, white, 0.3).
    expect_rel(small.radiance, 0.7 * 3.0 * ambient + glm::dvec3(0.3), 1e-14);
    const AirLight none = scene_air(20000.0, ambient, false);
    EXPECT_EQ(none.extinction, 0.0);
    EXPECT_EQ(none.radiance, glm::dvec3(0.0));
}

TEST(AirLight, ReferenceSeesASlabThroughTheAirExactly)
{
    // Looking straight down from 20 km onto a uniform slab [0, 100 m] lit by the sky alone:
    // J = a L_amb is constant, so along the ray (t0 = 19900 m to the slab, L = 100 m in it)
    //   L_fog = integral sigma e^(-sigma (t - t0)) [J e^(-beta t) + H (1 - e^(-beta t))] dt
    //         = J sigma e^(-beta t0) E + H ((1 - e^(-sigma L)) - sigma e^(-beta t0) E),
    //   E = (1 - e^(-(sigma + beta) L)) / (sigma + beta).
    const double sigma = 0.01, a = 0.9, top = 100.0, eye = 20000.0;
    const Medium m = kiri::test::slab_medium(0.0, top, sigma, a, 0.5, 5000.0, -5000.0);
    FogLighting light = sky_only();
    light.air = {1.0 / 20000.0, {0.8, 0.9, 1.0}};  // strong air, so that the test can tell
    const double beta = light.air.extinction, t0 = eye - top;
    const RayFog r = reference_ray({&m, {}}, nullptr, {0.0, 0.0, eye}, {0.0, 0.0, -1.0}, 2.0 * eye, light);
    const glm::dvec3 j = a * light.ambient;
    const double e = (1.0 - std::exp(-(sigma + beta) * top)) / (sigma + beta);
    const glm::dvec3 exact = j * sigma * std::exp(-beta * t0) * e +
        light.air.radiance * ((1.0 - std::exp(-sigma * top)) - sigma * std::exp(-beta * t0) * e);
    expect_rel(r.inscatter, exact, 1e-6);
    EXPECT_NEAR(r.transmittance, std::exp(-sigma * top), 1e-12);  // the air is not the fog's extinction
    // Without the air the fog is a L_amb (1 - T): the air changed it by a lot.
    const RayFog plain = reference_ray({&m, {}}, nullptr, {0.0, 0.0, eye}, {0.0, 0.0, -1.0}, 2.0 * eye, sky_only());
    expect_rel(plain.inscatter, j * (1.0 - std::exp(-sigma * top)), 1e-9);
    EXPECT_GT(luminance(r.inscatter), 1.3 * luminance(plain.inscatter));
    // A black world (no sky) has no air either.
    light.sky = false;
    const RayFog black = reference_ray({&m, {}}, nullptr, {0.0, 0.0, eye}, {0.0, 0.0, -1.0}, 2.0 * eye, light);
    EXPECT_EQ(black.inscatter, glm::dvec3(0.0));
}

TEST(AirLight, ReferenceHazesTheLitGroundAsTheTerrainPassDoes)
{
    // The ground at distance D is seen as L e^(-beta D) + H (1 - e^(-beta D)); a black ground
    // (--black-ground: the fog's light alone) stays black.
    const Heightfield ground =
        kiri::test::make_heightfield(11, 11, 1000.0, -5000.0, -5000.0, [](double, double) { return 0.0; });
    FogLighting light = sky_only();
    light.sun_radiance = glm::dvec3(2.0);
    light.sun_direction = {0.3, 0.2, 0.9};
    const glm::dvec3 eye(-3000.0, 0.0, 4000.0), w = glm::normalize(glm::dvec3(3000.0, 500.0, -4000.0));
    const RayFog plain = reference_ray({}, &ground, eye, w, 1e6, light);
    ASSERT_TRUE(plain.hit_terrain);
    light.air = {1.0 / 30000.0, {0.7, 0.8, 0.9}};
    const RayFog hazed = reference_ray({}, &ground, eye, w, 1e6, light);
    expect_rel(hazed.surface, light.air.seen(plain.surface, plain.distance), 1e-12);
    EXPECT_GT(light.air.haze(plain.distance), 0.1);
    ReferenceOptions black;
    black.shade_terrain = false;
    EXPECT_EQ(reference_ray({}, &ground, eye, w, 1e6, light, black).surface, glm::dvec3(0.0));
}
