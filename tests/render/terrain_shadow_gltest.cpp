// The terrain's shadow from the sun, one map for every pass: a 400 m ridge with a low sun
// behind it. Deep in its shadow the sun adds nothing, so the frame with the sun on must equal
// the frame with the sun off there, for the ground, the layers and the particles alike (as the
// CPU reference lights them: FogLighting's visibility V). In the sun the two frames differ.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "kiri/geometry/layers/layer_stack.hpp"
#include "kiri/geometry/particles/particles.hpp"
#include "kiri/geometry/scene/fog_spec.hpp"
#include "kiri/render/camera.hpp"
#include "kiri/render/renderer.hpp"
#include "render/render_fixture.hpp"

namespace {

using kiri::render::Camera;
using kiri::render::Image;
using kiri::render::Renderer;
using kiri::render::SunLight;
namespace g = kiri::geometry;

// A ridge along y through x = 0: `height` high, 40 m wide (a Gaussian), the plain at 0 around it.
g::Terrain ridge(double height = 400.0)
{
    g::Heightfield hf;
    hf.nx = hf.ny = 65;
    hf.dx = hf.dy = 20.0;
    hf.x0 = hf.y0 = -640.0;
    hf.z.resize(std::size_t(hf.nx) * std::size_t(hf.ny));
    hf.valid.assign(hf.z.size(), 1);
    for (int j = 0; j < hf.ny; ++j)
        for (int i = 0; i < hf.nx; ++i) {
            const double x = hf.x_of(i);
            hf.z[std::size_t(j) * std::size_t(hf.nx) + std::size_t(i)] =
                height * std::exp(-x * x / (2.0 * 40.0 * 40.0));
        }
    return g::Terrain(std::move(hf));
}

// The sun low in the east (+x), 17 degrees up: west of the ridge the plain and 100 m of air
// above it lie in its shadow for 1.3 km.
SunLight sun(bool on, bool shadows = true, int map_size = 1024)
{
    SunLight s;
    s.direction = {1.0, 0.0, 0.3};
    s.intensity = on ? 3.0 : 0.0;
    s.terrain_shadows = shadows;
    s.shadow_map_size = map_size;
    return s;
}

constexpr double shaded_x = -400.0, lit_x = 400.0;

Camera straight_down(double x)
{
    Camera c;
    c.position = {x, -1.0, 600.0};
    c.target = {x, 0.0, 0.0};
    c.fov_y_deg = 20.0;
    return c;
}

int centre_difference(const Image& a, const Image& b)
{
    const std::size_t k = (std::size_t(a.height / 2) * std::size_t(a.width) + std::size_t(a.width / 2)) * 4;
    int d = 0;
    for (int c = 0; c < 3; ++c)
        d = std::max(d, std::abs(int(a.rgba[k + c]) - int(b.rgba[k + c])));
    return d;
}

class TerrainShadowGl : public kiri::test::GlTest {
protected:
    // What the sun adds at the centre of a view straight down at x: the largest channel change
    // between the frames with the sun on and off.
    static int sun_adds(Renderer& r, double x, bool shadows, int map_size = 1024)
    {
        r.set_sun(sun(true, shadows, map_size));
        const Image on = r.render(straight_down(x), 48, 48);
        r.set_sun(sun(false, shadows, map_size));
        const Image off = r.render(straight_down(x), 48, 48);
        return centre_difference(on, off);
    }
};

TEST_F(TerrainShadowGl, TheGroundLiesInTheRidgesShadow)
{
    const g::Terrain t = ridge();
    Renderer r;
    r.set_terrain(t);
    EXPECT_LE(sun_adds(r, shaded_x, true), 1);
    EXPECT_GT(sun_adds(r, lit_x, true), 20);
    EXPECT_GT(sun_adds(r, shaded_x, false), 20);  // without shadows the sun reaches it
}

// A ridge 150 m high: its shadow on the plain ends 501 m west of its crest, where the ray towards
// the sun first clears it. On a coarse map (64 texels, about 20 m each: the default scene's is
// about 41 m over ridges a few hundred metres high) the ground's shadow still reaches that far: a
// point 120 m inside its end lies in it, one 120 m beyond it in the sun. The exponential map
// looked up 2 texels off the surface lit the first (the sun added 51 levels of 255), and most of
// the default scene's cast shadows with it.
TEST_F(TerrainShadowGl, ARidgesShadowReachesItsEndOnACoarseMap)
{
    const g::Terrain t = ridge(150.0);
    Renderer r;
    r.set_terrain(t);
    EXPECT_LE(sun_adds(r, -380.0, true, 64), 1);
    EXPECT_GT(sun_adds(r, -620.0, true, 64), 20);
    EXPECT_LE(sun_adds(r, -200.0, true, 64), 1);
}

TEST_F(TerrainShadowGl, TheLayersLieInTheRidgesShadow)
{
    const g::Terrain t = ridge();
    g::FogSpec spec;  // a lake 0..100 m over the plain on both sides of the ridge
    spec.footprint = g::rectangle_footprint({-600, -600}, {600, 600});
    spec.patch_size = 300.0;
    spec.surface = g::SurfaceKind::gregory;
    spec.fit.mode = g::FitMode::lake;
    spec.fit.altitude = 100.0;
    spec.tessellation.level = 5;
    g::BaseSurface surface = g::fog_control_surface(t, spec);
    g::fit_fog_surface(surface, t, spec);
    const g::Tessellation tessellation = g::tessellate(surface, spec.tessellation);
    g::LayerOptions o;
    o.count = 10;
    o.thickness = 100.0;
    o.base_offset = -100.0;
    o.shading = g::LayerShading::medium;
    o.optics.extinction = 0.02;
    o.optics.detail = 0.0;
    o.ground_fade = 5.0;
    const g::LayerBase base = g::make_layer_base(surface, tessellation, o);
    Renderer r;
    r.set_terrain(t);
    r.set_layers(base, o);
    EXPECT_LE(sun_adds(r, shaded_x, true), 1);
    EXPECT_GT(sun_adds(r, lit_x, true), 20);
    // The fog alone, without the terrain's shadows: the sun lights the layers over the dark ground.
    EXPECT_GT(sun_adds(r, shaded_x, false), 10);
}

TEST_F(TerrainShadowGl, TheParticlesLieInTheRidgesShadow)
{
    const g::Terrain t = ridge();
    g::ParticleCloud cloud;  // a sheet of particles 50 m up on either side of the ridge
    for (const double x0 : {shaded_x, lit_x})
        for (int j = -3; j <= 3; ++j)
            for (int i = -3; i <= 3; ++i)
                cloud.particles.push_back({{x0 + 15.0 * i, 15.0 * j, 50.0}, 20.0, 0.8, 0.9});
    Renderer r;
    r.set_terrain(t);
    r.set_particles(cloud);
    EXPECT_LE(sun_adds(r, shaded_x, true), 1);
    EXPECT_GT(sun_adds(r, lit_x, true), 20);
    r.clear_particles();  // the ground alone changes this much without shadows ...
    const int ground = sun_adds(r, shaded_x, false);
    r.set_particles(cloud);  // ... and the particles lit by the sun change it otherwise
    EXPECT_NE(sun_adds(r, shaded_x, false), ground);
}

}  // namespace
