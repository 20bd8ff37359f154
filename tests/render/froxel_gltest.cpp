// The froxel fog against the CPU reference ray marcher (geometry/reference_fog.hpp) at small
// resolution: homogeneous fog, height fog, a 2 m layer at 30 m, the Jacksboro fog lake with
// ridges through it; and what the pass must not do: NaN, g at +-1, work it need not do.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "kiri/geometry/froxel_options.hpp"
#include "kiri/geometry/medium.hpp"
#include "kiri/geometry/reference_fog.hpp"
#include "kiri/render/fog_error.hpp"
#include "kiri/render/renderer.hpp"
#include "render/render_fixture.hpp"

namespace {

namespace g = kiri::geometry;
using kiri::render::Camera;
using kiri::render::FogBuffer;
using kiri::render::FogError;
using kiri::render::Renderer;
using kiri::render::SunLight;

g::Terrain flat_ground(double half = 2000.0, double spacing = 50.0, double z = 0.0)
{
    g::Heightfield hf;
    hf.nx = hf.ny = int(std::lround(2.0 * half / spacing)) + 1;
    hf.dx = hf.dy = spacing;
    hf.x0 = hf.y0 = -half;
    hf.z.assign(std::size_t(hf.nx) * hf.ny, z);
    hf.valid.assign(hf.z.size(), 1);
    return g::Terrain(std::move(hf));
}

// A shell between bottom and top over [-half, half]^2, coverage 1.
g::Medium slab(double bottom, double top, double sigma, double half = 2000.0, double g_aniso = 0.6)
{
    g::MediumGrid grid;
    grid.nx = grid.ny = 3;
    grid.x0 = grid.y0 = -half;
    grid.dx = grid.dy = half;
    grid.floor.assign(9, bottom);
    grid.bottom.assign(9, bottom);
    grid.top.assign(9, top);
    grid.coverage.assign(9, 1.0);
    g::MediumOptions o;
    o.extinction = sigma;
    o.albedo = 0.9;
    o.anisotropy = g_aniso;
    o.top_density = 1.0;
    g::MediumDetail d;
    d.detail = 0.0;
    return g::Medium(std::move(grid), o, d);
}

SunLight sun()
{
    SunLight s;
    s.direction = {-0.6, 0.5, 0.45};
    s.color = {1.0, 0.95, 0.86};
    s.intensity = 3.0;
    s.ambient = {0.22, 0.28, 0.38};
    return s;
}

g::FogLighting lighting(const SunLight& s, const g::FroxelOptions& o)
{
    g::FogLighting l;
    l.sun_direction = s.direction;
    l.sun_radiance = s.color * s.intensity;
    l.ambient = s.ambient;
    l.terrain_shadows = o.terrain_shadows;
    l.fog_shadows = o.fog_shadows;
    l.scattering_octaves = o.scattering_octaves;
    return l;
}

struct Compared {
    FogError error;
    FogBuffer gpu;
    g::ReferenceImage reference;
};

class FroxelGl : public kiri::test::GlTest {
protected:
    // Renders the froxel fog and the reference of the same view and compares them.
    static Compared compare(const g::Terrain& terrain, const g::Medium* medium, const g::FroxelOptions& options,
                            const Camera& camera, int width, int height, const SunLight& light = sun(),
                            double min_depth = 0.0, double max_depth = HUGE_VAL)
    {
        Renderer r;
        r.set_terrain(terrain);
        r.set_sun(light);
        r.set_froxel_fog(medium, options);
        r.render(camera, width, height);
        Compared c;
        c.gpu = r.read_froxel_fog();
        g::ReferenceView view;
        view.eye = camera.position;
        view.target = camera.target;
        view.fov_y_deg = camera.fov_y_deg;
        view.width = width;
        view.height = height;
        view.max_depth = options.far;
        c.reference = g::render_reference_fog({medium, options.height_fog}, &terrain.heightfield(), view,
                                              lighting(light, options));
        c.error = kiri::render::compare_fog(c.gpu, c.reference, min_depth, max_depth);
        if (std::getenv("KIRI_FOG_DEBUG"))
            for (int y = 0; y < height; y += 4) {
                const std::size_t k = std::size_t(y) * width + width / 2;
                std::printf("DBG row %d depth %g/%g T %g/%g L %g/%g bg %g\n", y, c.gpu.depth[k], c.reference.depth[k], c.gpu.rgba[4 * k + 3],
                            c.reference.transmittance[k], c.gpu.rgba[4 * k + 1], c.reference.inscatter[k].y, c.reference.background[k].y);
            }
        std::printf("    fog pixels %d, silhouettes %d, mean %.4f, p99 %.4f, worst %.4f, |dT| %.4f, in-scatter %.4f "
                    "(reference %.2f s)\n",
                    c.error.fog_pixels, c.error.silhouette_pixels, c.error.mean_relative, c.error.p99_relative,
                    c.error.worst_relative, c.error.mean_transmittance_error, c.error.mean_inscatter_relative,
                    c.reference.seconds);
        return c;
    }
    static g::FroxelOptions small(int w, int h, int slices = 64)
    {
        g::FroxelOptions o;
        o.width = w;
        o.height = h;
        o.slices = slices;
        o.temporal = false;
        o.far = 6000.0;
        return o;
    }
};

TEST_F(FroxelGl, HomogeneousFog)
{
    const g::Terrain ground = flat_ground();
    const g::Medium fog = slab(0.0, 1500.0, 0.003);
    Camera c;
    c.position = {0.0, -1800.0, 60.0};
    c.target = {0.0, 0.0, 0.0};
    const Compared r = compare(ground, &fog, small(24, 14), c, 96, 54);
    EXPECT_GT(r.error.fog_pixels, 96 * 54 / 2);
    EXPECT_LT(r.error.mean_relative, 0.02);
    EXPECT_LT(r.error.p99_relative, 0.06);
}

TEST_F(FroxelGl, HeightFog)
{
    const g::Terrain ground = flat_ground();
    g::FroxelOptions o = small(24, 14);
    o.height_fog.extinction = 0.004;
    o.height_fog.base = 0.0;
    o.height_fog.scale_height = 40.0;
    o.height_fog.anisotropy = 0.5;
    Camera c;
    c.position = {0.0, -1800.0, 100.0};
    c.target = {0.0, 0.0, 0.0};
    const Compared r = compare(ground, nullptr, o, c, 96, 54);
    EXPECT_GT(r.error.fog_pixels, 96 * 54 / 2);
    EXPECT_LT(r.error.mean_relative, 0.02);
    // The worst pixels are sky just above the horizon, where the fog changes fastest from one
    // row to the next: 4 pixels a tile blur it.
    EXPECT_LT(r.error.p99_relative, 0.15);
}

TEST_F(FroxelGl, ThinLayerAt30Metres)
{
    // A 2 m layer of ground fog on flat ground seen from 5 m up, judged where the ground is 25
    // to 35 m away. Standard slicing (exponential from 1 m to the far side, 1 km) puts the
    // layer inside a slice or two there; fog-aware slicing spreads the tile's slices over it.
    const g::Terrain ground = flat_ground(1200.0, 10.0);
    const g::Medium layer = slab(0.0, 2.0, 0.05, 600.0);
    Camera c;
    c.position = {0.0, -30.0, 5.0};
    c.target = {0.0, 0.0, 0.0};
    g::FroxelOptions o = small(24, 14);
    o.far = 1000.0;
    const Compared aware = compare(ground, &layer, o, c, 96, 54, sun(), 25.0, 35.0);
    EXPECT_GT(aware.error.fog_pixels, 200);
    EXPECT_LT(aware.error.mean_relative, 0.02);
    EXPECT_LT(aware.error.p99_relative, 0.05);
    o.fog_aware = false;  // and one sample per froxel, like the engines
    o.density_samples = 1;
    const Compared standard64 = compare(ground, &layer, o, c, 96, 54, sun(), 25.0, 35.0);
    o.slices = 32;
    const Compared standard32 = compare(ground, &layer, o, c, 96, 54, sun(), 25.0, 35.0);
    EXPECT_GT(standard64.error.mean_relative, 2.0 * aware.error.mean_relative);
    EXPECT_GT(standard32.error.mean_relative, standard64.error.mean_relative);
    // The whole picture (9 m to the horizon) with fog-aware slicing.
    o.fog_aware = true;
    o.slices = 64;
    o.density_samples = 2;
    const Compared whole = compare(ground, &layer, o, c, 96, 54);
    EXPECT_LT(whole.error.mean_relative, 0.02);
}

}  // namespace

#include "kiri/geometry/scene.hpp"
#include "kiri/geometry/scene_fog.hpp"

namespace {

TEST_F(FroxelGl, JacksboroFogLake)
{
    // The bundled lake scene: fog filling the valleys to the 460 m contour, ridges rising
    // through it, the sun low in the west; its first camera.
    const g::Scene scene = g::load_scene(std::string(KIRI_DATA_DIR) + "/scenes/jacksboro_lake.json");
    const g::Terrain terrain = g::load_scene_terrain(scene);
    const g::SceneFog fog = g::author_scene_fog(scene, terrain);
    const g::Bounds3 b = terrain.bounds();
    const g::CameraSpec cam = scene.camera("", b.min, b.max);
    Camera c;
    c.position = cam.position;
    c.target = cam.target;
    c.fov_y_deg = cam.fov_y_deg;
    SunLight light;
    light.direction = scene.sun.direction;
    light.color = scene.sun.color;
    light.intensity = scene.sun.intensity;
    light.ambient = scene.sun.ambient;
    g::FroxelOptions o = small(160, 90);
    o.far = 60000.0;
    const Compared r = compare(terrain, &fog.medium, o, c, 320, 180, light);
    compare(terrain, &fog.medium, o, c, 640, 360, light);
    EXPECT_GT(r.error.fog_pixels, 500);
    EXPECT_LT(r.error.mean_relative, 0.02);
}

}  // namespace
