// The layer pass on an analytic terrain: fog where the ground is under the stack, none where a
// summit rises above it, nothing drawn below the ground or off-screen, uploads only once.
#include <gtest/gtest.h>

#include <cmath>

#include "kiri/geometry/fog_spec.hpp"
#include "kiri/geometry/layer_stack.hpp"
#include "kiri/render/camera.hpp"
#include "kiri/render/renderer.hpp"
#include "render/render_fixture.hpp"

namespace {

using kiri::render::Camera;
using kiri::render::Image;
using kiri::render::Renderer;
namespace g = kiri::geometry;

class LayersGl : public kiri::test::GlTest {
protected:
    // A fog lake over the Gaussian hill: stack from 50 m to 150 m, the 300 m summit above it.
    static void SetUpTestSuite()
    {
        GlTest::SetUpTestSuite();
        hill() = std::make_unique<g::Terrain>(kiri::test::gaussian_hill());
        g::FogSpec spec;
        spec.footprint = g::rectangle_footprint({-560, -560}, {560, 560});
        spec.patch_size = 280.0;
        spec.surface = g::SurfaceKind::gregory;
        spec.fit.mode = g::FitMode::lake;
        spec.fit.altitude = 150.0;
        spec.tessellation.level = 6;
        authored() = std::make_unique<g::AuthoredSurface>(g::author_base_surface(*hill(), spec));
    }
    static void TearDownTestSuite()
    {
        authored().reset();
        hill().reset();
    }
    static std::unique_ptr<g::Terrain>& hill()
    {
        static std::unique_ptr<g::Terrain> t;
        return t;
    }
    static std::unique_ptr<g::AuthoredSurface>& authored()
    {
        static std::unique_ptr<g::AuthoredSurface> a;
        return a;
    }
    static g::LayerOptions options(double base_offset = -100.0)
    {
        g::LayerOptions o;
        o.count = 10;
        o.thickness = 100.0;
        o.base_offset = base_offset;
        o.opacity = 0.3;
        o.detail = 0.0;
        o.ground_fade = 5.0;
        return o;
    }
    static Camera above()
    {
        Camera c;
        c.position = {0.0, -1.0, 3000.0};
        c.target = {0.0, 0.0, 0.0};
        c.fov_y_deg = 30.0;
        return c;
    }
    static const std::uint8_t* pixel(const Image& image, const glm::dvec2& p)
    {
        return &image.rgba[(std::size_t(p.y) * image.width + std::size_t(p.x)) * 4];
    }
};

double luminance(const std::uint8_t* p) { return 0.3 * p[0] + 0.6 * p[1] + 0.1 * p[2]; }

TEST_F(LayersGl, FogCoversTheLowGroundNotTheSummit)
{
    const int w = 200, h = 200;
    Renderer renderer;
    renderer.set_terrain(*hill());
    const Image bare = renderer.render(above(), w, h);
    const g::LayerOptions o = options();
    const g::LayerBase base = g::make_layer_base(authored()->surface, authored()->tessellation, o);
    renderer.set_layers(base, o);
    const Image fog = renderer.render(above(), w, h);
    EXPECT_EQ(renderer.last_stats().layers, 10);
    // The summit (300 m) rises above the stack's top (150 m): unchanged.
    const glm::dvec2 summit = kiri::render::project_to_pixel(above(), {0.0, 0.0, 300.0}, w, h);
    EXPECT_LE(std::abs(luminance(pixel(fog, summit)) - luminance(pixel(bare, summit))), 1.0);
    // The plain at 450 m from the centre (ground ~ 60 m, under 90 m of fog): brighter, greyer.
    for (const glm::dvec2 xy : {glm::dvec2(450, 0), glm::dvec2(0, -450), glm::dvec2(-420, 380)}) {
        const double z = hill()->height(xy.x, xy.y);
        ASSERT_LT(z, 80.0);
        const glm::dvec2 p = kiri::render::project_to_pixel(above(), {xy.x, xy.y, z}, w, h);
        EXPECT_GT(luminance(pixel(fog, p)), luminance(pixel(bare, p)) + 20.0) << xy.x << ", " << xy.y;
    }
}

TEST_F(LayersGl, StackBelowTheGroundDrawsNothing)
{
    const int w = 160, h = 120;
    Renderer renderer;
    renderer.set_terrain(*hill());
    const Image bare = renderer.render(above(), w, h);
    const g::LayerOptions o = options(-1000.0);  // 850 .. 950 m below the lake's top: underground
    const g::LayerBase base = g::make_layer_base(authored()->surface, authored()->tessellation, o);
    renderer.set_layers(base, o);
    const Image fog = renderer.render(above(), w, h);
    EXPECT_EQ(renderer.last_stats().layers, 10);  // drawn, and hidden by the depth test
    EXPECT_EQ(fog.rgba, bare.rgba);
}

TEST_F(LayersGl, OffScreenStackIsCulledAndUploadsHappenOnce)
{
    const int w = 160, h = 120;
    Renderer renderer;
    renderer.set_terrain(*hill());
    const g::LayerOptions o = options();
    const g::LayerBase base = g::make_layer_base(authored()->surface, authored()->tessellation, o);
    renderer.set_layers(base, o);
    renderer.render(above(), w, h);
    EXPECT_EQ(renderer.last_stats().uploads, 3);  // terrain, layer base, ground heights
    renderer.set_layers(base, o);
    renderer.render(above(), w, h);
    EXPECT_EQ(renderer.last_stats().uploads, 0);
    Camera away;
    away.position = {0.0, -2000.0, 400.0};
    away.target = {0.0, -6000.0, 400.0};
    renderer.render(away, w, h);
    EXPECT_EQ(renderer.last_stats().layers, 0);
}

}  // namespace
