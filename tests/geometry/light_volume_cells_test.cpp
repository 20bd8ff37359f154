// The baked light-transport volume (light_volume.hpp, light_volume_bake.hpp) where one (x, y) cell
// holds two bodies of fog that see very different diffuse light, against the path tracer as the
// oracle: a thin layer beside a thick slab (the column normalisation), and a pool deep in the
// terrain's shadow beside a sunlit slab (each side of the shadow's own light).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <numbers>
#include <utility>

#include <glm/geometric.hpp>

#include "fog_test_terrains.hpp"
#include "kiri/geometry/medium/light_volume.hpp"
#include "kiri/geometry/medium/medium.hpp"
#include "kiri/geometry/reference/light_volume_bake.hpp"
#include "kiri/geometry/reference/path_tracer.hpp"
#include "kiri/geometry/reference/reference_fog.hpp"

using namespace kiri::geometry;

namespace {

// Uniform fog (sigma 0.02, albedo 0.99, g 0.8, no noise) in columns along x from 0 to 1,000 m,
// each from the ground at 0 up to top(x) (none where it is 0), over y in [y0, y0 + 2 dy].
Medium fog_columns_along_x(double y0, double dy, const std::function<double(double)>& top)
{
    MediumGrid grid;
    grid.nx = 41;
    grid.ny = 3;
    grid.x0 = 0.0;
    grid.y0 = y0;
    grid.dx = 25.0;
    grid.dy = dy;
    for (int j = 0; j < grid.ny; ++j)
        for (int i = 0; i < grid.nx; ++i) {
            const double t = top(grid.x0 + i * grid.dx);
            grid.floor.push_back(0.0);
            grid.bottom.push_back(0.0);
            grid.top.push_back(t);
            grid.coverage.push_back(t > 0.0 ? 1.0 : 0.0);
        }
    MediumOptions mo;
    mo.extinction = 0.02;
    mo.albedo = 0.99;
    mo.anisotropy = 0.8;
    mo.top_density = 1.0;
    MediumDetail md;
    md.detail = 0.0;
    return Medium(std::move(grid), mo, md);
}

// A sun `elevation` degrees up at `azimuth`, of unit radiance in a black sky, under the model
// `baked`; a bake of one (x, y) cell and `levels` levels; the reference and 4,000 paths a pixel
// over a black ground.
struct OneCell {
    FogLighting light;
    LightVolumeOptions bake;
    ReferenceOptions reference;
    PathTracerOptions paths;
    OneCell(double elevation, double azimuth, int levels)
    {
        const double e = elevation * std::numbers::pi / 180.0;
        light.sun_direction = {std::cos(e) * std::cos(azimuth), std::cos(e) * std::sin(azimuth), std::sin(e)};
        light.sun_radiance = glm::dvec3(1.0);
        light.sky = false;
        light.multiple_scattering = MultipleScattering::baked;
        bake.photons = 40000;
        bake.threads = 2;
        bake.max_side = 1;  // one cell in (x, y)
        bake.levels = levels;
        reference.shade_terrain = false;
        paths.samples = 4000;
        paths.sky = PathSky::none;
        paths.ground = PathGround::black;
    }
};

}  // namespace

TEST(LightVolume, AThinLayerBesideAThickBodyInOneCellGetsItsOwnLight)
{
    // One (x, y) cell holds two bodies of fog 200 m apart: a slab 150 m thick (x < 500) and a layer
    // 10 m thin (x > 700), under a sun 35 degrees up from the north (both lit alike), on a black
    // ground. The thin layer's diffuse light is its own (tau 0.2 of it) and a little of the slab's
    // across the gap; a cell that averages the two gives it the slab's (optical depth 3). Looking
    // down on the thin layer: the model (single scattering plus the baked volume) against every
    // order path traced; with the cell's diffuse light unnormalised the model is several times too
    // bright there, while over the slab both agree.
    const Heightfield ground =
        kiri::test::make_heightfield(21, 21, 100.0, -500.0, -1000.0, [](double, double) { return 0.0; });
    const Medium m = fog_columns_along_x(-500.0, 500.0, [](double x) {
        return x <= 500.0 ? 150.0 : x >= 700.0 ? 10.0 : 0.0;
    });
    OneCell cell(35.0, 0.5 * std::numbers::pi, 4);
    FogLighting& light = cell.light;
    LightVolumeOptions& o = cell.bake;
    const ReferenceOptions& ro = cell.reference;
    const PathTracerOptions& po = cell.paths;
    const glm::dvec3 down = glm::normalize(glm::dvec3(0.1, 0.05, -1.0));
    const glm::dvec3 over_thin(850.0, 0.0, 300.0), over_thick(250.0, 0.0, 300.0);
    light.light_volume =
        std::make_shared<const LightVolume>(bake_light_volume({&m, {}}, &ground, light.sun_direction, o));
    ASSERT_EQ(light.light_volume->nx, 1);
    ASSERT_EQ(light.light_volume->ny, 1);
    FogLighting unnormalised = light;
    o.column_normalised = false;
    unnormalised.light_volume =
        std::make_shared<const LightVolume>(bake_light_volume({&m, {}}, &ground, light.sun_direction, o));
    for (const glm::dvec3& origin : {over_thin, over_thick}) {
        const PathEstimate truth = path_traced_ray({&m, {}}, &ground, origin, down, 1e6, light, po, 11);
        const double model = reference_ray({&m, {}}, &ground, origin, down, 1e6, light, ro).inscatter.x;
        const double old = reference_ray({&m, {}}, &ground, origin, down, 1e6, unnormalised, ro).inscatter.x;
        const double bound = 0.25 * truth.radiance.x + 3.0 * truth.std_error.x;
        EXPECT_NEAR(model, truth.radiance.x, bound) << "over x = " << origin.x;
        if (origin.x > 700.0) {
            EXPECT_GT(old, 1.6 * truth.radiance.x) << "the unnormalised cell, over the thin layer";
        }
    }
}

TEST(LightVolume, FogDeepInTheTerrainsShadowKeepsItsOwnDimLight)
{
    // One (x, y) cell holds a slab of fog 100 m thick in the sun (x < 350) and, behind a wall 300 m
    // high (x from 420 to 460), a pool 30 m deep (x from 500 to 700) in its shadow: the sun 20
    // degrees up from the west leaves the ground dark up to x = 1,250. (The shadow's tops are
    // sampled 62.5 m apart over this one cell, bilinear between: fog against the wall's sunlit face
    // would count partly in the shadow.) The pool sees only the light
    // that the slab scatters over the wall, a small fraction of the slab's own; a cell that keeps
    // one mean gives the pool the slab's. Looking down on the pool and on the slab: single scattering
    // plus the baked volume against every order path traced. Without the shadow's parts the pool is
    // many times too bright.
    const Heightfield ground = kiri::test::make_heightfield(
        61, 11, 25.0, -250.0, -125.0, [](double x, double) { return x > 420.0 && x < 460.0 ? 300.0 : 0.0; });
    const Medium m = fog_columns_along_x(-100.0, 100.0, [](double x) {
        return x <= 350.0 ? 100.0 : x >= 500.0 && x <= 700.0 ? 30.0 : 0.0;
    });
    OneCell cell(20.0, std::numbers::pi, 2);  // the sun from the west
    FogLighting& light = cell.light;
    const LightVolumeOptions& o = cell.bake;
    const ReferenceOptions& ro = cell.reference;
    const PathTracerOptions& po = cell.paths;
    auto volume = std::make_shared<LightVolume>(bake_light_volume({&m, {}}, &ground, light.sun_direction, o));
    ASSERT_EQ(volume->nx, 1);
    ASSERT_TRUE(volume->has_shadow_parts());
    EXPECT_GT(volume->shadow_top_at(600.0, 0.0), 30.0);  // the pool under the wall's shadow
    EXPECT_NEAR(volume->shadow_top_at(200.0, 0.0), 0.0, 1e-9);
    light.light_volume = volume;
    // The same volume read as one mean a cell: what the lookup gave before.
    auto one_mean = std::make_shared<LightVolume>(*volume);
    one_mean->class_means.clear();
    FogLighting whole = light;
    whole.light_volume = one_mean;
    const glm::dvec3 down = glm::normalize(glm::dvec3(0.05, 0.02, -1.0));
    const glm::dvec3 over_slab(200.0, 0.0, 250.0), over_pool(600.0, 0.0, 250.0);
    const PathEstimate slab_truth = path_traced_ray({&m, {}}, &ground, over_slab, down, 1e6, light, po, 13);
    ASSERT_GT(slab_truth.radiance.x, 0.01);
    for (const glm::dvec3& origin : {over_pool, over_slab}) {
        const PathEstimate truth =
            origin == over_slab ? slab_truth : path_traced_ray({&m, {}}, &ground, origin, down, 1e6, light, po, 13);
        const double model = reference_ray({&m, {}}, &ground, origin, down, 1e6, light, ro).inscatter.x;
        const double old = reference_ray({&m, {}}, &ground, origin, down, 1e6, whole, ro).inscatter.x;
        std::printf("    over x = %.0f: path traced %.5f +- %.5f, baked %.5f, one mean a cell %.5f\n", origin.x,
                    truth.radiance.x, truth.std_error.x, model, old);
        // Within 30 % and the path tracer's noise, and 1 % of the slab's light (the pool's is nearly 0).
        EXPECT_NEAR(model, truth.radiance.x,
                    0.3 * truth.radiance.x + 3.0 * truth.std_error.x + 0.01 * slab_truth.radiance.x)
            << "over x = " << origin.x;
        if (origin == over_pool) {
            EXPECT_GT(old, 0.15 * slab_truth.radiance.x) << "one mean a cell gives the pool the slab's light";
        }
    }
}
