#pragma once
// Shared by the froxel GL tests: small analytic scenes and the comparison of the froxel fog with
// the CPU reference ray marcher (geometry/reference_fog.hpp) at small resolution.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include <glm/geometric.hpp>

#include "kiri/geometry/volume/froxel_options.hpp"
#include "kiri/geometry/medium/light_volume.hpp"
#include "kiri/geometry/medium/medium.hpp"
#include "kiri/geometry/reference/reference_fog.hpp"
#include "kiri/render/fog_error.hpp"
#include "kiri/render/renderer.hpp"
#include "kiri/render/scene_rendering.hpp"
#include "render/render_fixture.hpp"

namespace kiri::test {

namespace g = kiri::geometry;
using kiri::render::Camera;
using kiri::render::FogBuffer;
using kiri::render::FogError;
using kiri::render::Renderer;
using kiri::render::SunLight;

inline g::Terrain flat_ground(double half = 2000.0, double spacing = 50.0, double z = 0.0)
{
    g::Heightfield hf;
    hf.nx = hf.ny = int(std::lround(2.0 * half / spacing)) + 1;
    hf.dx = hf.dy = spacing;
    hf.x0 = hf.y0 = -half;
    hf.z.assign(std::size_t(hf.nx) * hf.ny, z);
    hf.valid.assign(hf.z.size(), 1);
    return g::Terrain(std::move(hf));
}

// The terrain z = height(x, y) on a 20 m grid over [-half, half]^2.
template <class Height>
g::Terrain sampled_terrain(double half, Height height)
{
    g::Heightfield hf;
    hf.nx = hf.ny = int(std::lround(2.0 * half / 20.0)) + 1;
    hf.dx = hf.dy = 20.0;
    hf.x0 = hf.y0 = -half;
    hf.z.resize(std::size_t(hf.nx) * hf.ny);
    hf.valid.assign(hf.z.size(), 1);
    for (int j = 0; j < hf.ny; ++j)
        for (int i = 0; i < hf.nx; ++i)
            hf.z[std::size_t(j) * hf.nx + i] = height(hf.x_of(i), hf.y_of(j));
    return g::Terrain(std::move(hf));
}

// Parallel valleys along y, 400 m apart and 160 m deep (z = 80 (1 - cos(2 pi x / 400))), on a
// 20 m grid over [-half, half]^2: narrow valleys to hold threads of fog.
inline g::Terrain parallel_valleys(double half)
{
    return sampled_terrain(half, [](double x, double) { return 80.0 * (1.0 - std::cos(2.0 * M_PI * x / 400.0)); });
}

// A shell between bottom and top over [-half, half]^2, coverage 1.
// Single scattering unless told (the tests judge the froxel machinery; the octaves are one sum);
// octaves 0: the fitted multiple scattering.
inline g::Medium slab(double bottom, double top, double sigma, double half = 2000.0, double g_aniso = 0.6,
                      int octaves = 1)
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
    o.multiple_scattering = octaves == 0 ? g::MultipleScattering::fitted : g::MultipleScattering::octaves;
    o.scattering_octaves = std::max(octaves, 1);
    g::MediumDetail d;
    d.detail = 0.0;
    return g::Medium(std::move(grid), o, d);
}

inline SunLight sun()
{
    SunLight s;
    s.direction = {-0.6, 0.5, 0.45};
    s.color = {1.0, 0.95, 0.86};
    s.intensity = 3.0;
    s.ambient = {0.22, 0.28, 0.38};
    return s;
}

// The renderer's lighting model for the reference, with the air the renderer draws over `terrain`.
inline g::FogLighting lighting(const SunLight& s, const g::FroxelOptions& o, const g::Medium* medium,
                               const g::Terrain& terrain)
{
    g::FogLighting l;
    l.air = kiri::render::terrain_air(&terrain, s.ambient, s.sky);
    l.sun_direction = s.direction;
    l.sun_radiance = s.color * s.intensity;
    l.ambient = s.ambient;
    l.terrain_shadows = o.terrain_shadows;
    l.fog_shadows = o.fog_shadows;
    l.multiple_scattering = g::multiple_scattering_of(medium);
    l.scattering_octaves = g::scattering_octaves_of(medium);
    return l;
}

struct Compared {
    FogError error;
    FogBuffer gpu;
    g::ReferenceImage reference;
};

inline void expect_finite(const FogBuffer& f)
{
    ASSERT_FALSE(f.rgba.empty());
    int bad = 0;
    for (std::size_t k = 0; k < f.rgba.size(); ++k)
        bad += !std::isfinite(f.rgba[k]) || f.rgba[k] < 0.0f;
    for (std::size_t k = 3; k < f.rgba.size(); k += 4)
        bad += f.rgba[k] > 1.0f;
    EXPECT_EQ(bad, 0) << "values that are NaN, infinite, negative or a transmittance above 1";
}

class FroxelGl : public kiri::test::GlTest {
protected:
    // Renders the froxel fog and the reference of the same view and compares them.
    static Compared compare(const g::Terrain& terrain, const g::Medium* medium, const g::FroxelOptions& options,
                            const Camera& camera, int width, int height, const SunLight& light = sun(),
                            double min_depth = 0.0, double max_depth = HUGE_VAL,
                            std::shared_ptr<const g::LightVolume> light_volume = nullptr)
    {
        Renderer r;
        r.set_light_volume(light_volume, medium);
        r.set_terrain(terrain);
        // The sun's shadow map as the options set it (SceneRendering::sun does the same).
        SunLight shadowed = light;
        shadowed.terrain_shadows = options.terrain_shadows;
        shadowed.shadow_map_size = options.shadow_map_size;
        shadowed.esm_sharpness = options.esm_sharpness;
        r.set_sun(shadowed);
        r.set_froxel_fog(medium, options);
        r.render(camera, width, height);
        Compared c;
        c.gpu = r.read_froxel_fog();
        const g::ReferenceView view = kiri::render::reference_view(camera, width, height, options.far);
        g::FogLighting lit = lighting(light, options, medium, terrain);
        lit.light_volume = light_volume;
        c.reference = g::render_reference_fog({medium, options.height_fog}, &terrain.heightfield(), view, lit);
        c.error = kiri::render::compare_fog(c.gpu, c.reference, min_depth, max_depth);
        expect_finite(c.gpu);
        std::printf(
            "    fog pixels %d, silhouettes %d, mean %.4f, p99 %.4f, worst %.4f, |dT| %.4f, in-scatter %.4f "
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

}  // namespace kiri::test
