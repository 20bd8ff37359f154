// The layers drawn at reduced resolution (Renderer::set_layer_resolution) against the same
// layers at full resolution: a thin fog over a flat plain seen at a grazing angle, the case
// where testing the low-resolution layers against one full-resolution pixel's depth cut the fog
// into stripes (rows whose lowest layers lay behind that pixel's ground).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "kiri/geometry/layers/layer_stack.hpp"
#include "kiri/geometry/scene/fog_spec.hpp"
#include "kiri/render/camera.hpp"
#include "kiri/render/renderer.hpp"
#include "render/render_fixture.hpp"

namespace {

using kiri::render::Camera;
using kiri::render::Image;
using kiri::render::Renderer;
namespace g = kiri::geometry;

g::Terrain plain()
{
    g::Heightfield hf;
    hf.nx = hf.ny = 65;
    hf.dx = hf.dy = 1000.0;
    hf.x0 = hf.y0 = -32000.0;
    hf.z.assign(std::size_t(hf.nx) * std::size_t(hf.ny), 0.0);
    hf.valid.assign(hf.z.size(), 1);
    return g::Terrain(std::move(hf));
}

// Mean luminance of each row of the frame's middle half (columns), in grey levels.
std::vector<double> row_means(const Image& image)
{
    std::vector<double> rows(std::size_t(image.height), 0.0);
    const int x0 = image.width / 4, x1 = 3 * image.width / 4;
    for (int y = 0; y < image.height; ++y) {
        for (int x = x0; x < x1; ++x) {
            const std::uint8_t* p = &image.rgba[(std::size_t(y) * std::size_t(image.width) + std::size_t(x)) * 4];
            rows[std::size_t(y)] += 0.3 * p[0] + 0.6 * p[1] + 0.1 * p[2];
        }
        rows[std::size_t(y)] /= double(x1 - x0);
    }
    return rows;
}

class LayersReducedGl : public kiri::test::GlTest {};

// A thin sheet of fog over the plain: the layers' base and options (the renderer keeps
// references to both).
struct Sheet {
    g::LayerOptions options;
    g::LayerBase base;
    //! Gives `r` the plain and this sheet's layers.
    void draw_with(Renderer& r, const g::Terrain& t) const
    {
        r.set_terrain(t);
        r.set_layers(base, options);
    }
};

Sheet sheet(const g::Terrain& t)
{
    g::FogSpec spec;  // a sheet of fog 20 m thick over the whole plain
    spec.footprint = g::rectangle_footprint({-30000, -30000}, {30000, 30000});
    spec.patch_size = 2000.0;
    spec.surface = g::SurfaceKind::gregory;
    spec.fit.mode = g::FitMode::lake;
    spec.fit.altitude = 23.0;
    spec.tessellation.level = 4;
    g::BaseSurface surface = g::fog_control_surface(t, spec);
    g::fit_fog_surface(surface, t, spec);
    const g::Tessellation tessellation = g::tessellate(surface, spec.tessellation);
    g::LayerOptions o;
    o.count = 15;
    o.thickness = 23.0;
    o.base_offset = -23.0;
    o.shading = g::LayerShading::medium;
    o.optics.extinction = 0.03;
    o.optics.detail = 0.0;
    o.ground_fade = 5.0;
    return {o, g::make_layer_base(surface, tessellation, o)};
}

Camera overview()
{
    Camera c;  // 97 km away, looking down 32 degrees (a derived overview of a 60 km tile)
    c.position = {-39000.0, -79000.0, 51000.0};
    c.target = {0.0, 0.0, 0.0};
    c.fov_y_deg = 45.0;
    return c;
}

TEST_F(LayersReducedGl, ThinFogOverAPlainAtAGrazingAngleHasNoStripes)
{
    const g::Terrain t = plain();
    const Sheet fog = sheet(t);
    Renderer r;
    fog.draw_with(r, t);
    const Camera c = overview();
    const int w = 640, h = 360;
    r.set_layer_resolution(1.0);
    const std::vector<double> full = row_means(r.render(c, w, h));
    r.set_layer_resolution(0.5);
    const std::vector<double> reduced = row_means(r.render(c, w, h));
    // Rows of fog over the plain (the sheet covers the frame's lower half). A stripe is a row
    // darker than its neighbours: the reduced frame's rows change from one to the next no more
    // than 0.3 grey levels (measured 0.07; the full frame's 0.15; tested against one pixel's
    // depth instead of the farthest, 0.54), and its fog stays as bright as the full frame's
    // (measured 0.7 levels darker on average).
    double jump_full = 0.0, jump_reduced = 0.0, sum = 0.0;
    int rows = 0;
    for (int y = h / 2; y < h; ++y) {
        const std::size_t k = std::size_t(y);
        if (y > h / 2) {
            jump_full = std::max(jump_full, std::abs(full[k] - full[k - 1]));
            jump_reduced = std::max(jump_reduced, std::abs(reduced[k] - reduced[k - 1]));
        }
        sum += full[k] - reduced[k];
        ++rows;
    }
    std::printf("row-to-row change: reduced %.3f, full %.3f levels; reduced darker by %.2f\n", jump_reduced, jump_full,
                sum / rows);
    EXPECT_LT(jump_reduced, 0.3);
    EXPECT_LT(std::abs(sum / rows), 1.5);
}

// The reduced target keeps 320 x 180 texels: a frame of that size or smaller draws its layers at
// its own resolution whatever the setting (the same picture as at 1.0), a larger one at the
// setting's scale, never finer than the frame.
TEST_F(LayersReducedGl, ASmallFrameKeepsTheReducedTargetsFloor)
{
    const g::Terrain t = plain();
    const Sheet fog = sheet(t);
    Renderer r;
    fog.draw_with(r, t);
    const Camera c = overview();
    const auto frame = [&](double scale, int w, int h) {
        r.set_layer_resolution(scale);
        return r.render(c, w, h).rgba;
    };
    // (Compared as whole pictures: EXPECT_EQ would print every byte.)
    EXPECT_TRUE(frame(0.5, 160, 90) == frame(1.0, 160, 90));
    EXPECT_TRUE(frame(0.25, 320, 180) == frame(1.0, 320, 180));
    EXPECT_FALSE(frame(0.5, 480, 270) == frame(1.0, 480, 270));  // 320 x 180 of 480 x 270: reduced
}

}  // namespace
