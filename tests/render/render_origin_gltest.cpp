// A scene near 1e7 m draws as it does at home (the renderer's origin, render/src/render_origin.hpp):
// the same terrain, layers, particles and froxel fog (its Medium's detail noise, a height fog
// with an extent, a baked light volume) built around (0, 0) and around (1e7 + 250, 1e7 - 130),
// each seen from the same place relative to it, give the same picture in every renderer. Floats
// there have a 1 m step: a renderer that hands the GPU world coordinates loses the fog's edges,
// the terrain's shape and the noise (shown failing with the origin held at zero).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "geometry/particle_test_clouds.hpp"
#include "kiri/geometry/layers/layer_stack.hpp"
#include "kiri/geometry/medium/light_volume.hpp"
#include "kiri/geometry/scene/fog_spec.hpp"
#include "kiri/geometry/volume/froxel_options.hpp"
#include "kiri/render/camera.hpp"
#include "kiri/render/renderer.hpp"
#include "render/render_fixture.hpp"

namespace {

namespace g = kiri::geometry;
using kiri::render::Camera;
using kiri::render::RadianceImage;
using kiri::render::Renderer;

const glm::dvec3 far_away(1e7 + 250.0, 1e7 - 130.0, 0.0);

// Everything of the scene built around `at`.
struct Scene {
    std::unique_ptr<g::Terrain> terrain;
    g::LayerBase base;
    g::LayerOptions layer_options;
    g::ParticleCloud cloud;
    std::unique_ptr<g::Medium> medium;
    std::shared_ptr<g::LightVolume> light;
    g::FroxelOptions froxel;
    Camera camera;
};

// The noise of the Medium and of the layers is the world's (it does not move with a scene), so
// the moved scene's drifts by `at` with the wind: the same fog, moved.
constexpr double drift_time = 1000.0;

g::LayerOptions layer_options(const glm::dvec3& at = glm::dvec3(0.0))
{
    g::LayerOptions o;
    o.count = 10;
    o.thickness = 100.0;
    o.base_offset = -100.0;
    o.shading = g::LayerShading::source;
    o.opacity = 0.3;
    o.optics.detail = 0.6;  // the layers' noise, which must stay in place
    o.optics.detail_scale = 90.0;
    o.optics.wind = glm::dvec2(at) / drift_time;
    o.optics.time = drift_time;
    o.ground_fade = 5.0;
    return o;
}

// The lake over the Gaussian hill (layers_gltest's), at home.
const g::LayerBase& home_base()
{
    static const g::LayerBase base = [] {
        const g::Terrain hill = kiri::test::gaussian_hill();
        g::FogSpec spec;
        spec.footprint = g::rectangle_footprint({-560, -560}, {560, 560});
        spec.patch_size = 280.0;
        spec.surface = g::SurfaceKind::gregory;
        spec.fit.mode = g::FitMode::lake;
        spec.fit.altitude = 150.0;
        spec.tessellation.level = 6;
        g::BaseSurface surface = g::fog_control_surface(hill, spec);
        g::fit_fog_surface(surface, hill, spec);
        const g::Tessellation tessellation = g::tessellate(surface, spec.tessellation);
        return g::make_layer_base(surface, tessellation, layer_options());
    }();
    return base;
}

Scene scene_at(const glm::dvec3& at)
{
    Scene s;
    g::Heightfield hf = kiri::test::gaussian_hill().heightfield();
    hf.x0 += at.x;
    hf.y0 += at.y;
    s.terrain = std::make_unique<g::Terrain>(std::move(hf));

    s.base = home_base();
    for (glm::dvec3& p : s.base.position)
        p += at;
    s.base.centre += glm::dvec2(at);
    s.base.min += at;
    s.base.max += at;
    s.layer_options = layer_options(at);

    s.cloud = kiri::test::ball_cloud(1500, 220.0, 40.0, 0.6);
    for (g::Particle& p : s.cloud.particles)
        p.position += at + glm::dvec3(-150.0, -250.0, 250.0 - 1000.0);

    g::MediumGrid grid;
    grid.nx = grid.ny = 9;
    grid.dx = grid.dy = 140.0;
    grid.x0 = at.x - 560.0;
    grid.y0 = at.y - 560.0;
    for (int j = 0; j < 9; ++j)
        for (int i = 0; i < 9; ++i) {
            const double ground = s.terrain->height(grid.x0 + i * grid.dx, grid.y0 + j * grid.dy);
            grid.floor.push_back(std::max(ground, 20.0));
            grid.bottom.push_back(20.0);
            grid.top.push_back(std::max(ground, 160.0 + 4.0 * i));
            grid.coverage.push_back(i == 0 || j == 0 || i == 8 || j == 8 ? 0.0 : 1.0);
        }
    g::MediumOptions mo;
    mo.extinction = 0.006;
    mo.albedo = 0.95;
    mo.anisotropy = 0.5;
    mo.detail = 0.6;  // the Medium's noise, which must stay in place
    mo.detail_scale = 110.0;
    mo.wind = glm::dvec2(at) / drift_time;
    mo.time = drift_time;
    mo.multiple_scattering = g::MultipleScattering::baked;
    s.medium = std::make_unique<g::Medium>(std::move(grid), mo, g::medium_detail(mo));

    // A light volume whose light grows eastwards and upwards: read where the fog is, or not.
    s.light = std::make_shared<g::LightVolume>();
    g::LightVolume& v = *s.light;
    v.nx = v.ny = 8;
    v.nz = 4;
    v.bands = 1;
    v.x0 = at.x - 560.0;
    v.y0 = at.y - 560.0;
    v.dx = v.dy = 140.0;
    for (int k = 0; k < v.nz; ++k)
        for (int j = 0; j < v.ny; ++j)
            for (int i = 0; i < v.nx; ++i)
                v.moments.push_back(0.05 + 0.04 * i + 0.02 * k);

    s.froxel.width = 32;
    s.froxel.height = 18;
    s.froxel.slices = 64;
    s.froxel.far = 4000.0;
    s.froxel.height_fog.extinction = 0.0008;
    s.froxel.height_fog.base = 30.0;
    s.froxel.height_fog.scale_height = 60.0;
    s.froxel.height_fog.min = glm::dvec2(at) + glm::dvec2(-400.0, -700.0);
    s.froxel.height_fog.max = glm::dvec2(at) + glm::dvec2(300.0, 200.0);

    s.camera.position = at + glm::dvec3(-300.0, -1500.0, 420.0);
    s.camera.target = at + glm::dvec3(0.0, 0.0, 90.0);
    s.camera.fov_y_deg = 45.0;
    return s;
}

enum class Part { terrain, layers, particles, froxels };

RadianceImage draw(const Scene& s, Part part, glm::dvec3* origin = nullptr)
{
    Renderer r;
    kiri::render::SunLight sun;
    sun.direction = {-0.5, 0.4, 0.5};
    r.set_sun(sun);
    // The light volume before the terrain: whatever the order, everything takes the origin.
    if (part == Part::froxels)
        r.set_light_volume(s.light, s.medium.get());
    r.set_terrain(*s.terrain);
    if (part == Part::layers)
        r.set_layers(s.base, s.layer_options);
    if (part == Part::particles)
        r.set_particles(s.cloud);
    if (part == Part::froxels)
        r.set_froxel_fog(s.medium.get(), s.froxel);
    r.render(s.camera, 96, 54);
    if (origin)
        *origin = r.origin();
    return r.read_radiance();
}

// Mean |Y_a - Y_b| over the mean Y_b.
double mean_difference(const RadianceImage& a, const RadianceImage& b)
{
    double diff = 0.0, sum = 0.0;
    for (std::size_t k = 0; k + 3 < a.rgba.size(); k += 4) {
        const auto y = [](const RadianceImage& i, std::size_t k) {
            return 0.2126 * i.rgba[k] + 0.7152 * i.rgba[k + 1] + 0.0722 * i.rgba[k + 2];
        };
        diff += std::abs(y(a, k) - y(b, k));
        sum += y(b, k);
    }
    return sum > 0.0 ? diff / sum : 0.0;
}

class RenderOrigin : public kiri::test::GlTest {};

TEST_F(RenderOrigin, EveryRendererDrawsASceneNearTenMillionMetresAsAtHome)
{
    const Scene home = scene_at(glm::dvec3(0.0)), moved = scene_at(far_away);
    const RadianceImage bare = draw(home, Part::terrain);
    for (const auto& [part, name] : {std::pair{Part::terrain, "terrain"}, std::pair{Part::layers, "layers"},
                                     std::pair{Part::particles, "particles"}, std::pair{Part::froxels, "froxels"}}) {
        glm::dvec3 home_origin, moved_origin;
        const RadianceImage a = draw(home, part, &home_origin), b = draw(moved, part, &moved_origin);
        EXPECT_EQ(home_origin, glm::dvec3(0.0));
        EXPECT_EQ(moved_origin, glm::dvec3(1e7, 1e7, 0.0));
        ASSERT_EQ(a.rgba.size(), b.rgba.size());
        bool finite = true;
        for (float v : b.rgba)
            finite = finite && std::isfinite(v);
        EXPECT_TRUE(finite) << name;
        const double difference = mean_difference(b, a), fog = mean_difference(a, bare);
        std::printf("    %-9s near 1e7 m against at home: %.5f %% (the fog itself: %.2f %% of the frame)\n", name,
                    100.0 * difference, 100.0 * fog);
        if (part != Part::terrain) {
            EXPECT_GT(fog, 0.02) << name;  // there is fog to lose: 8.7, 2.6 and 2.7 % of the frame
        }
        // Measured at most 5e-6 (float rounding; the froxels 7e-5, since their marches light each
        // ray at its own points: without the light volume 2e-7, so its lookups there, at points
        // whose last bits differ between the two scenes, 250 and 130 m apart from the origin,
        // not understood further). With the origin held at zero (world floats):
        // terrain 2.7e-4, layers 1.0e-3, particles 4.5e-4, froxels 1.1e-2.
        EXPECT_LT(difference, part == Part::froxels ? 2e-4 : 1e-5) << name;
    }
}

}  // namespace
