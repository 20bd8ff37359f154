// The froxel fog under the lighting model `baked` against the CPU reference, which reads the same
// light-transport volume (geometry/reference/light_volume_bake.hpp): a slab seen from inside (its
// multiple scattering from the volume, not without it), a height fog whose light the volume's
// cells hold above a thin Medium's top, under a lifted Medium's floor and beyond the Medium's
// grid, and a pool deep in the terrain's shadow beside a sunlit slab in one cell (each part's
// light).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include <glm/geometric.hpp>

#include "kiri/geometry/reference/light_volume_bake.hpp"
#include "render/froxel_fixture.hpp"

namespace {

using namespace kiri::test;

// The slab of slab() lit by the model `baked`: its multiple scattering from a light volume.
g::Medium baked_slab(double bottom, double top, double sigma, double half)
{
    const g::Medium plain = slab(bottom, top, sigma, half);
    g::MediumOptions o = plain.options();
    o.multiple_scattering = g::MultipleScattering::baked;
    o.albedo = 0.99;
    o.anisotropy = 0.8;
    return g::Medium(plain.grid(), o, plain.detail());
}

// A quick bake of the fog and height fog over the ground under the sun (12 cells a side, 6 levels).
std::shared_ptr<const g::LightVolume> small_bake(const g::Medium& fog, const g::HeightFog& haze,
                                                 const g::Terrain& ground, const SunLight& light)
{
    g::LightVolumeOptions bake;
    bake.photons_per_column = 200;
    bake.levels = 6;
    bake.max_side = 12;
    return std::make_shared<const g::LightVolume>(
        g::bake_light_volume({&fog, haze}, &ground.heightfield(), glm::normalize(light.direction), bake));
}

TEST_F(FroxelGl, BakedMultipleScatteringIsTheReferencesLight)
{
    // A slab 300 m thick (optical thickness 1.5, albedo 0.99, g 0.8) seen from inside, lit by
    // the baked volume in both the froxels and the CPU reference: the froxels read the same
    // moments (light_volume.glsl) and agree as they do in single scattering. Without the volume
    // the froxels draw single scattering, far from the baked reference: the volume is read.
    const g::Terrain ground = flat_ground();
    const g::Medium fog = baked_slab(0.0, 300.0, 0.005, 2000.0);
    const SunLight light = sun();
    const auto volume = small_bake(fog, {}, ground, light);
    ASSERT_FALSE(volume->empty());
    Camera c;
    c.position = {0.0, -1500.0, 150.0};
    c.target = {300.0, 0.0, 120.0};
    const g::FroxelOptions o = small(24, 14);
    const Compared with = compare(ground, &fog, o, c, 96, 54, light, 0.0, HUGE_VAL, volume);
    EXPECT_GT(with.error.fog_pixels, 96 * 54 / 2);
    EXPECT_LT(with.error.mean_relative, 0.03);
    // The same froxels without the volume against the same reference.
    Renderer single;
    single.set_terrain(ground);
    SunLight shadowed = light;
    shadowed.terrain_shadows = o.terrain_shadows;
    single.set_sun(shadowed);
    single.set_froxel_fog(&fog, o);
    single.render(c, 96, 54);
    const kiri::render::FogError without = kiri::render::compare_fog(single.read_froxel_fog(), with.reference);
    std::printf("    without the volume: mean %.4f\n", without.mean_relative);
    EXPECT_GT(without.mean_relative, 4.0 * with.error.mean_relative);
    EXPECT_GT(without.mean_relative, 0.05);
}

// A height fog (extinction 0.01, albedo 0.99, g 0.6) of the given base and scale height in the
// froxels' options over a baked slab from bottom to top (sigma 1/m), and their light volume baked
// over the ground.
struct BakedHaze {
    g::Medium fog;
    g::FroxelOptions options;
    std::shared_ptr<const g::LightVolume> volume;
};

BakedHaze baked_haze(const g::FroxelOptions& options, double bottom, double top, double sigma, double base,
                     double scale_height, const g::Terrain& ground, const SunLight& light)
{
    BakedHaze h{baked_slab(bottom, top, sigma, 2000.0), options, nullptr};
    h.options.height_fog.extinction = 0.01;
    h.options.height_fog.base = base;
    h.options.height_fog.scale_height = scale_height;
    h.options.height_fog.albedo = 0.99;
    h.options.height_fog.anisotropy = 0.6;
    h.volume = small_bake(h.fog, h.options.height_fog, ground, light);
    EXPECT_FALSE(h.volume->empty());
    return h;
}

// The froxels from inside such a height fog are the baked reference's within 3 % over most pixels.
void expect_the_references(const Compared& with, const char* where)
{
    std::printf("    baked height fog %s: mean %.4f over %d fog pixels\n", where, with.error.mean_relative,
                with.error.fog_pixels);
    EXPECT_GT(with.error.fog_pixels, 96 * 54 / 2);
    EXPECT_LT(with.error.mean_relative, 0.03);
}

TEST_F(FroxelGl, BakedLightOfAHeightFogAboveTheMediumsTopIsTheReferences)
{
    // A height fog reaching 320 m (8 scale heights of 40 m) over a Medium 20 m deep, seen from
    // inside it: the froxels light the height fog above the Medium's top from the volume's cells,
    // which reach up to the height fog's top (geometry::LightVolume::shell), as the reference
    // does. Before, that light was missing from both (the bake followed no photon above the
    // Medium's box).
    const g::Terrain ground = flat_ground();
    const SunLight light = sun();
    const BakedHaze h = baked_haze(small(24, 14), 0.0, 20.0, 0.002, 0.0, 40.0, ground, light);
    ASSERT_DOUBLE_EQ(h.volume->haze_top, 320.0);
    Camera c;
    c.position = {0.0, -1500.0, 100.0};
    c.target = {300.0, 0.0, 110.0};
    expect_the_references(compare(ground, &h.fog, h.options, c, 96, 54, light, 0.0, HUGE_VAL, h.volume),
                          "above the Medium");
}

TEST_F(FroxelGl, BakedLightOfAHeightFogUnderALiftedMediumsFloorIsTheReferences)
{
    // A blanket from 120 to 160 m over a height fog that fills the ground's first 60 m, seen
    // from inside the height fog: the volume's cells reach down to the ground under the
    // Medium's floor (geometry::LightVolume::floors, read by lv_floor_at), as the reference's do
    // (54 % off it with the GLSL reading no floors).
    const g::Terrain ground = flat_ground();
    const SunLight light = sun();
    const BakedHaze h = baked_haze(small(24, 14), 120.0, 160.0, 0.004, 60.0, 20.0, ground, light);
    ASSERT_FALSE(h.volume->floors.empty());
    ASSERT_DOUBLE_EQ(h.volume->floor_at(0.0, 0.0), 0.0);
    Camera c;
    c.position = {0.0, -1500.0, 30.0};
    c.target = {300.0, 0.0, 40.0};
    expect_the_references(compare(ground, &h.fog, h.options, c, 96, 54, light, 0.0, HUGE_VAL, h.volume),
                          "under the Medium");
}

TEST_F(FroxelGl, BakedLightOfAHeightFogBeyondTheMediumsGridIsTheReferences)
{
    // A height fog over a ground 8 km across, a Medium 2 km across in its middle, seen from
    // inside the height fog beyond the Medium's grid and looking away from it. There the CPU
    // takes the edge cells' light (geometry::Medium::column clamps to its edge columns, coverage
    // 0), and so do the froxels (light_volume.glsl). Before, the froxels put no baked light there:
    // the default scene's top camera had its height fog along the DEM's edges at a tenth of the
    // reference's light.
    const g::Terrain ground = flat_ground(4000.0, 100.0);
    const SunLight light = sun();
    BakedHaze h{baked_slab(0.0, 60.0, 0.004, 1000.0), small(24, 14), nullptr};
    h.options.height_fog.extinction = 0.01;
    h.options.height_fog.base = 0.0;
    h.options.height_fog.scale_height = 20.0;
    h.options.height_fog.albedo = 0.99;
    h.options.height_fog.anisotropy = 0.6;
    h.volume = small_bake(h.fog, h.options.height_fog, ground, light);
    ASSERT_FALSE(h.volume->empty());
    Camera c;
    c.position = {0.0, -1500.0, 40.0};
    c.target = {-300.0, -3500.0, 30.0};
    expect_the_references(compare(ground, &h.fog, h.options, c, 96, 54, light, 0.0, HUGE_VAL, h.volume),
                          "beyond the Medium's grid");
}

TEST_F(FroxelGl, FogDeepInTheTerrainsShadowTakesItsPartsLightAsTheReferenceDoes)
{
    // One cell of the volume holds a sunlit slab of fog (x < 350) and, behind a wall 300 m high
    // (x from 420 to 460) under a sun 20 degrees up from the west, a pool 30 m deep (x from 500
    // to 700) in its shadow, whose diffuse light is nearly none (LightVolume's
    // FogDeepInTheTerrainsShadowKeepsItsOwnDimLight). Seen from above, the froxels read each
    // part's light as the reference does: the pool stays dark beside the lit slab. Read as one
    // mean a cell, the pool had a fifth of the slab's light.
    g::Heightfield hf;
    hf.nx = 121;
    hf.ny = 41;
    hf.dx = hf.dy = 25.0;
    hf.x0 = -1000.0;
    hf.y0 = -500.0;
    for (int j = 0; j < hf.ny; ++j)
        for (int i = 0; i < hf.nx; ++i)
            hf.z.push_back(hf.x_of(i) > 420.0 && hf.x_of(i) < 460.0 ? 300.0 : 0.0);
    hf.valid.assign(hf.z.size(), 1);
    const g::Terrain ground(std::move(hf));
    g::MediumGrid grid;
    grid.nx = 41;
    grid.ny = 3;
    grid.x0 = 0.0;
    grid.y0 = -250.0;
    grid.dx = 25.0;
    grid.dy = 250.0;
    for (int j = 0; j < grid.ny; ++j)
        for (int i = 0; i < grid.nx; ++i) {
            const double x = grid.x0 + i * grid.dx;
            const double top = x <= 350.0 ? 100.0 : x >= 500.0 && x <= 700.0 ? 30.0 : 0.0;
            grid.floor.push_back(0.0);
            grid.bottom.push_back(0.0);
            grid.top.push_back(top);
            grid.coverage.push_back(top > 0.0 ? 1.0 : 0.0);
        }
    g::MediumOptions mo;
    mo.extinction = 0.02;
    mo.albedo = 0.99;
    mo.anisotropy = 0.8;
    mo.top_density = 1.0;
    mo.multiple_scattering = g::MultipleScattering::baked;
    g::MediumDetail md;
    md.detail = 0.0;
    const g::Medium fog(std::move(grid), mo, md);
    SunLight light = sun();
    light.direction = {-std::cos(20.0 * M_PI / 180.0), 0.0, std::sin(20.0 * M_PI / 180.0)};
    light.ambient = glm::vec3(0.0f);
    g::LightVolumeOptions bake;
    bake.photons = 40000;
    bake.max_side = 1;  // one cell in (x, y)
    bake.levels = 2;
    const auto volume = std::make_shared<const g::LightVolume>(
        g::bake_light_volume({&fog, {}}, &ground.heightfield(), glm::normalize(light.direction), bake));
    ASSERT_TRUE(volume->has_shadow_parts());
    const g::FroxelOptions o = small(24, 14);
    // The mean in-scattered luminance over a view straight down on x, from 300 m up.
    const auto seen_from_above = [&](double x, double& gpu, double& reference) {
        Camera c;
        c.position = {x, 0.0, 300.0};
        c.target = {x, 1.0, 0.0};
        const Compared with = compare(ground, &fog, o, c, 48, 27, light, 0.0, HUGE_VAL, volume);
        gpu = reference = 0.0;
        const std::size_t n = with.reference.inscatter.size();
        for (std::size_t k = 0; k < n; ++k) {
            const glm::dvec3 r = with.reference.inscatter[k];
            reference += (0.2126 * r.x + 0.7152 * r.y + 0.0722 * r.z) / double(n);
            gpu += (0.2126 * with.gpu.rgba[k * 4] + 0.7152 * with.gpu.rgba[k * 4 + 1] +
                    0.0722 * with.gpu.rgba[k * 4 + 2]) /
                double(n);
        }
        std::printf("    over x = %.0f: froxels %.5f, reference %.5f\n", x, gpu, reference);
    };
    double slab_gpu, slab_reference, pool_gpu, pool_reference;
    seen_from_above(175.0, slab_gpu, slab_reference);
    seen_from_above(600.0, pool_gpu, pool_reference);
    ASSERT_GT(slab_reference, 0.0);
    EXPECT_NEAR(slab_gpu, slab_reference, 0.1 * slab_reference);
    EXPECT_LT(pool_reference, 0.05 * slab_reference);
    EXPECT_NEAR(pool_gpu, pool_reference, 0.05 * slab_reference);
}

}  // namespace
