// Overlay meshes (overlay_mesh.hpp): drawn where they project, blended with their alpha,
// hidden behind the terrain, edges only in wireframe, lines, and bad arrays refused.
#include <gtest/gtest.h>

#include <cstdint>

#include "kiri/geometry/core/error.hpp"
#include "kiri/render/renderer.hpp"
#include "render/render_fixture.hpp"

namespace {

using kiri::render::Camera;
using kiri::render::Image;
using kiri::render::OverlayMesh;
using kiri::render::OverlayStyle;
using kiri::render::Renderer;

constexpr int W = 160, H = 120;

// Straight down onto the hill (peak 300 m at the origin, plain at 0 m).
Camera top_camera()
{
    Camera c;
    c.position = {0.0, -1.0, 3000.0};
    c.target = {0.0, 0.0, 0.0};
    c.fov_y_deg = 40.0;
    return c;
}

// An unlit square of half-size s at height z, centred on the origin.
OverlayMesh square(double s, double z, glm::vec4 color)
{
    OverlayMesh m;
    const float a = float(s), h = float(z);
    m.positions = {{-a, -a, h}, {a, -a, h}, {a, a, h}, {-a, a, h}};
    m.colors.assign(4, color);
    m.indices = {0, 1, 2, 0, 2, 3};
    return m;
}

struct Rgb {
    int r, g, b;
};
Rgb at(const Image& im, int x, int y)
{
    const std::uint8_t* p = &im.rgba[(std::size_t(y) * im.width + x) * 4];
    return {p[0], p[1], p[2]};
}

class OverlayGl : public kiri::test::GlTest {
protected:
    kiri::geometry::Terrain hill = kiri::test::gaussian_hill();
    Renderer renderer;
    void SetUp() override { renderer.set_terrain(hill); }
};

TEST_F(OverlayGl, OpaqueSquareAboveTheHillCoversTheCentre)
{
    const Image bare = renderer.render(top_camera(), W, H);
    renderer.set_overlay("square", square(200.0, 400.0, {1.0f, 0.0f, 0.0f, 1.0f}));
    const Image covered = renderer.render(top_camera(), W, H);
    const Rgb c = at(covered, W / 2, H / 2);
    EXPECT_EQ(c.r, 255);
    EXPECT_EQ(c.g, 0);
    EXPECT_EQ(c.b, 0);
    // Far from the square the frame is unchanged; the stats list the overlay pass.
    const Rgb corner = at(covered, 2, 2), bare_corner = at(bare, 2, 2);
    EXPECT_EQ(corner.r, bare_corner.r);
    EXPECT_EQ(corner.g, bare_corner.g);
    ASSERT_EQ(renderer.last_stats().passes.size(), 7u);  // the sun's shadow map first
    EXPECT_EQ(renderer.last_stats().passes[6].pass, "overlays");
}

TEST_F(OverlayGl, HalfAlphaBlendsHalfway)
{
    const Image bare = renderer.render(top_camera(), W, H);
    renderer.set_overlay("square", square(200.0, 400.0, {1.0f, 1.0f, 1.0f, 1.0f}));
    renderer.set_overlay_style("square", {.color = {1.0f, 1.0f, 1.0f, 0.5f}});
    const Image blended = renderer.render(top_camera(), W, H);
    const Rgb b = at(bare, W / 2, H / 2), c = at(blended, W / 2, H / 2);
    // 8-bit blending: 0.5 * 255 + 0.5 * under, within one step of rounding.
    EXPECT_NEAR(c.r, 0.5 * 255 + 0.5 * b.r, 1.0);
    EXPECT_NEAR(c.g, 0.5 * 255 + 0.5 * b.g, 1.0);
    EXPECT_NEAR(c.b, 0.5 * 255 + 0.5 * b.b, 1.0);
}

TEST_F(OverlayGl, TheTerrainHidesWhatIsBelowIt)
{
    const Image bare = renderer.render(top_camera(), W, H);
    // At 100 m the square is under the hill's top (300 m) and above the plain far out.
    renderer.set_overlay("square", square(800.0, 100.0, {1.0f, 0.0f, 0.0f, 1.0f}));
    const Image im = renderer.render(top_camera(), W, H);
    const Rgb centre = at(im, W / 2, H / 2), centre_bare = at(bare, W / 2, H / 2);
    EXPECT_EQ(centre.r, centre_bare.r);
    EXPECT_EQ(centre.g, centre_bare.g);
    const Rgb edge = at(im, W / 2 + 35, H / 2);  // about 560 m out: the hill is ~24 m high there
    EXPECT_EQ(edge.r, 255);
    EXPECT_EQ(edge.g, 0);
}

TEST_F(OverlayGl, WireframeDrawsEdgesOnlyAndHiddenOverlaysDrawNothing)
{
    const Image bare = renderer.render(top_camera(), W, H);
    renderer.set_overlay("square", square(200.0, 400.0, {1.0f, 0.0f, 0.0f, 1.0f}));
    renderer.set_overlay_style("square", {.wireframe = true});
    const Image wire = renderer.render(top_camera(), W, H);
    const Rgb inside = at(wire, W / 2 - 10, H / 2 + 5), inside_bare = at(bare, W / 2 - 10, H / 2 + 5);
    EXPECT_EQ(inside.r, inside_bare.r) << "the inside of a wireframe square is not filled";
    int red = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const Rgb p = at(wire, x, y);
            red += p.r > 200 && p.g < 60;
        }
    // Four sides of ~2 x 200 m at ~2600 m away: ~26 pixels each, plus the diagonal.
    EXPECT_GT(red, 80);
    EXPECT_LT(red, 400);
    renderer.set_overlay_style("square", {.visible = false});
    const Image hidden = renderer.render(top_camera(), W, H);
    EXPECT_EQ(hidden.rgba, bare.rgba);
    EXPECT_EQ(renderer.last_stats().passes.size(), 6u);
}

TEST_F(OverlayGl, LinesAreDrawnAndBadArraysRefused)
{
    OverlayMesh line;
    line.primitive = OverlayMesh::Primitive::lines;
    line.positions = {{-500.0f, 0.0f, 600.0f}, {500.0f, 0.0f, 600.0f}};
    line.colors.assign(2, {0.0f, 0.0f, 1.0f, 1.0f});
    line.indices = {0, 1};
    renderer.set_overlay("line", line);
    const Image im = renderer.render(top_camera(), W, H);
    int blue = 0;
    for (int x = 0; x < W; ++x)
        for (int y = H / 2 - 2; y <= H / 2 + 2; ++y) {
            const Rgb p = at(im, x, y);
            blue += p.b > 200 && p.r < 60 && p.g < 60;
        }
    EXPECT_GT(blue, 40);  // the line crosses about 64 columns at this distance

    OverlayMesh bad = line;
    bad.indices = {0, 2};
    EXPECT_THROW(renderer.set_overlay("bad", bad), kiri::Error);
    bad.indices = {0};
    EXPECT_THROW(renderer.set_overlay("bad", bad), kiri::Error);
    bad = line;
    bad.normals.resize(1);
    EXPECT_THROW(renderer.set_overlay("bad", bad), kiri::Error);
}

}  // namespace
