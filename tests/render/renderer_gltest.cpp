#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "kiri/render/camera.hpp"
#include "kiri/render/renderer.hpp"
#include "render/render_fixture.hpp"

namespace {

using kiri::render::Camera;
using kiri::render::Image;
using kiri::render::Renderer;

Camera oblique_camera()
{
    Camera c;
    c.position = {-300.0, -1500.0, 900.0};
    c.target = {0.0, 0.0, 80.0};
    c.fov_y_deg = 50.0;
    return c;
}

class RendererGl : public kiri::test::GlTest {};

TEST(Camera, TargetProjectsToImageCentreAndFovEdgeToTopRow)
{
    Camera c;
    c.position = {10.0, -200.0, 50.0};
    c.target = {10.0, 0.0, 50.0};
    c.fov_y_deg = 60.0;
    const glm::dvec2 centre = kiri::render::project_to_pixel(c, c.target, 640, 480);
    EXPECT_NEAR(centre.x, 320.0, 1e-9);
    EXPECT_NEAR(centre.y, 240.0, 1e-9);
    // A point at half the vertical field of view above the axis lands on the top edge, and
    // one to the right at the horizontal half-angle on the right edge.
    const double t = std::tan(M_PI / 6.0) * 200.0;
    const glm::dvec2 top = kiri::render::project_to_pixel(c, {10.0, 0.0, 50.0 + t}, 640, 480);
    EXPECT_NEAR(top.x, 320.0, 1e-9);
    EXPECT_NEAR(top.y, 0.0, 1e-9);
    const glm::dvec2 right = kiri::render::project_to_pixel(c, {10.0 + t * 640.0 / 480.0, 0.0, 50.0}, 640, 480);
    EXPECT_NEAR(right.x, 640.0, 1e-9);
}

TEST_F(RendererGl, ACoarseTerrainLevelDrawsAFractionOfTheGridAndTheSameGround)
{
    // A frame drawn small (80x60) at every 4th sample of a 257 x 257 hill: a sixteenth of the
    // triangles (and the fans of the border), the ground (and the surround around it) where it
    // was: every terrain point picked on the coarse level lies on the hill within the coarse
    // cells' chord error, and the picture differs from the whole grid's by little.
    const kiri::geometry::Terrain hill = kiri::test::gaussian_hill(257, 5.0);
    Renderer renderer;
    renderer.set_terrain(hill);
    const Camera camera = oblique_camera();
    const int w = 80, h = 60;
    const Image full = renderer.render(camera, w, h);
    const int full_triangles = renderer.last_stats().terrain_triangles;
    EXPECT_EQ(full_triangles, 256 * 256 * 2);
    std::vector<std::optional<glm::dvec3>> full_picks;
    for (int y = 0; y < h; y += 5)
        for (int x = 0; x < w; x += 5)
            full_picks.push_back(renderer.pick(x, y));
    renderer.set_terrain_resolution(0.25);
    const Image coarse = renderer.render(camera, w, h);
    const int coarse_triangles = renderer.last_stats().terrain_triangles;
    EXPECT_GT(coarse_triangles, full_triangles / 16);
    EXPECT_LT(coarse_triangles, full_triangles / 14);
    // Each pixel sees the ground where the whole grid put it, within the coarse cells' chord
    // error (a quarter of a metre on this hill) and the depth buffer's steps.
    // The surround too, drawn at the level's samples along the grid's sides (its rings meet
    // the level's border sample by sample).
    int picked = 0, on_surround = 0;
    std::size_t k = 0;
    for (int y = 0; y < h; y += 5)
        for (int x = 0; x < w; x += 5, ++k)
            if (const auto seen = renderer.pick(x, y); seen && full_picks[k]) {
                ++picked;
                on_surround += std::max(std::abs(full_picks[k]->x), std::abs(full_picks[k]->y)) > 640.0;
                EXPECT_LT(glm::length(*seen - *full_picks[k]), 2.0) << x << ", " << y;
            }
    EXPECT_GT(picked, 100);
    EXPECT_GT(on_surround, 20);
    std::printf("    %d picks, %d of them on the surround\n", picked, on_surround);
    double difference = 0.0;
    for (std::size_t k = 0; k < full.rgba.size(); ++k)
        difference += std::abs(double(full.rgba[k]) - double(coarse.rgba[k]));
    difference /= 255.0 * double(full.rgba.size());
    std::printf("    coarse level: %d of %d triangles, mean difference %.4f\n", coarse_triangles, full_triangles,
                difference);
    EXPECT_LT(difference, 0.01);
}

TEST_F(RendererGl, TheResolvedDepthIsThePixelCentres)
{
    // A tilted plane seen at a grazing angle: the depth every pass after the resolve reads at a
    // pixel (pick unprojects it through the pixel's centre) must be where the centre's ray meets
    // the plane. A copy of one MSAA sample put it 0.4 pixel off: tens of metres at a distance.
    kiri::geometry::Heightfield hf;
    hf.nx = hf.ny = 65;
    hf.dx = hf.dy = 40.0;
    hf.x0 = hf.y0 = -1280.0;
    const auto plane = [](double x, double y) { return 200.0 + 0.1 * x + 0.3 * y; };
    for (int j = 0; j < hf.ny; ++j)
        for (int i = 0; i < hf.nx; ++i)
            hf.z.push_back(plane(hf.x_of(i), hf.y_of(j)));
    hf.valid.assign(hf.z.size(), 1);
    const kiri::geometry::Terrain ground(std::move(hf));
    Renderer renderer;
    renderer.set_terrain(ground, 1.0, false);
    Camera camera;
    // Above the terrain's box: its near plane then keeps the depth's precision (an eye inside
    // the box gets a near plane of centimetres).
    camera.position = {-100.0, -3000.0, 1100.0};
    camera.target = {0.0, 0.0, 200.0};
    camera.fov_y_deg = 30.0;
    const int w = 64, h = 48;
    renderer.render(camera, w, h);
    double worst = 0.0;
    int checked = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const auto seen = renderer.pick(x, y);
            if (!seen || std::abs(seen->x) > 1100.0 || std::abs(seen->y) > 1100.0)
                continue;  // sky, or the plane's rim, where a pixel straddles two surfaces
            // The centre's ray (through the picked point) meets the plane at t: pick's distance
            // against it.
            const glm::dvec3 d = glm::normalize(*seen - camera.position);
            const glm::dvec3 e = camera.position;
            const double t = (plane(e.x, e.y) - e.z) / (d.z - 0.1 * d.x - 0.3 * d.y);
            const double rel = glm::length(*seen - e) / t - 1.0;
            worst = std::max(worst, std::abs(rel));
            ++checked;
        }
    EXPECT_GT(checked, w * h / 3);
    // Measured: 1.6e-7 (a copy of sample 0: 7.9e-3).
    EXPECT_LT(worst, 1e-4) << "relative distance along the ray";
}

TEST_F(RendererGl, AtAnEdgeTheResolvedDepthIsTheSurfaceTheCentreSees)
{
    // A hill against the plain far behind it: pixels on its silhouette straddle two surfaces.
    // The resolved depth there is the surface the pixel's centre most likely sees: the plane
    // through the samples on the side of the jump most of them are on (the nearest sample where
    // they split evenly), not the plane fitted through both sides (four samples split two and
    // two across the diagonals fit one exactly: a depth in mid-air, where the fog would end).
    const kiri::geometry::Terrain hill = kiri::test::gaussian_hill(129, 20.0, 400.0, 300.0);
    Renderer renderer;
    renderer.set_terrain(hill, 1.0, false);
    Camera camera;
    camera.position = {0.0, -1400.0, 700.0};  // above the terrain's box (its top 400 m)
    camera.target = {0.0, 0.0, 300.0};
    camera.fov_y_deg = 30.0;
    const int w = 96, h = 72;
    renderer.render(camera, w, h);
    const auto distance = [&](int x, int y) {
        const auto p = renderer.pick(x, y);
        return p ? glm::length(*p - camera.position) : -1.0;
    };
    int edges = 0, right = 0;
    for (int y = 1; y + 1 < h; ++y)
        for (int x = 1; x + 1 < w; ++x) {
            const double t = distance(x, y);
            if (t < 0.0)
                continue;
            double near = t, far = t;  // the nearest and the farthest of its 3x3
            for (int k = 0; k < 9; ++k)
                if (const double n = distance(x + k % 3 - 1, y + k / 3 - 1); n > 0.0) {
                    near = std::min(near, n);
                    far = std::max(far, n);
                }
            if (far < 1.3 * near)
                continue;  // no jump here
            ++edges;
            const glm::dvec3 d = glm::normalize(*renderer.pick(x, y) - camera.position);
            const auto hit = hill.intersect_ray(camera.position, d);
            right += hit && std::abs(t / hit->t - 1.0) < 0.01;  // the surface the centre sees
        }
    EXPECT_GT(edges, 60);
    // Measured: 112 of 130 (the nearest sample at every edge instead: 90 of 126).
    EXPECT_GT(right, 0.8 * edges) << edges << " pixels at a jump";
}

TEST_F(RendererGl, KnownTerrainPointsAppearAtTheirProjectedPixels)
{
    const kiri::geometry::Terrain hill = kiri::test::gaussian_hill();
    Renderer renderer;
    renderer.set_terrain(hill);
    const Camera camera = oblique_camera();
    const int w = 320, h = 240;
    renderer.render(camera, w, h);
    int checked = 0;
    // Points on the hill's near flank and the plain in front of it: visible from the camera.
    for (double x : {-400.0, -150.0, 0.0, 200.0, 450.0})
        for (double y : {-500.0, -300.0, -120.0}) {
            const glm::dvec3 world(x, y, hill.height(x, y));
            const glm::dvec2 px = kiri::render::project_to_pixel(camera, world, w, h);
            ASSERT_GT(px.x, 0.0);
            ASSERT_LT(px.x, w);
            const auto seen = renderer.pick(int(px.x), int(px.y));
            ASSERT_TRUE(seen.has_value()) << "nothing drawn at the projection of " << x << ", " << y;
            // The pixel centre is at most half a pixel diagonal away from the projection: its
            // footprint on the ground at this distance bounds the error.
            const double distance = glm::length(world - camera.position);
            const double pixel_m = 2.0 * distance * std::tan(glm::radians(camera.fov_y_deg) / 2.0) / h;
            const double slant =
                1.0 / std::max(0.2, std::abs(glm::dot(glm::normalize(world - camera.position), hill.normal(x, y))));
            EXPECT_LT(glm::length(*seen - world), 1.5 * pixel_m * slant) << "at " << x << ", " << y;
            EXPECT_NEAR(seen->z, hill.height(seen->x, seen->y), 0.5 * pixel_m * slant);
            ++checked;
        }
    EXPECT_EQ(checked, 15);
    // The sky above the horizon has no surface.
    EXPECT_FALSE(renderer.pick(w / 2, 0).has_value());
}

TEST_F(RendererGl, StaticSceneUploadsOnce)
{
    const kiri::geometry::Terrain hill = kiri::test::gaussian_hill();
    Renderer renderer;
    renderer.set_terrain(hill);
    renderer.render(oblique_camera(), 64, 48);
    EXPECT_EQ(renderer.last_stats().uploads, 1);
    renderer.set_terrain(hill);
    renderer.render(oblique_camera(), 64, 48);
    EXPECT_EQ(renderer.last_stats().uploads, 0);
    renderer.set_terrain(hill, 2.0);
    renderer.render(oblique_camera(), 64, 48);
    EXPECT_EQ(renderer.last_stats().uploads, 1);
    // The sun's shadow map of the terrain (rebuilt: a new exaggeration), then the frame.
    ASSERT_EQ(renderer.last_stats().passes.size(), 6u);
    EXPECT_EQ(renderer.last_stats().passes[0].pass, "shadow map");
    EXPECT_EQ(renderer.last_stats().shadow_map_updates, 2);
    EXPECT_EQ(renderer.last_stats().passes[2].pass, "terrain");
    EXPECT_EQ(renderer.last_stats().passes[3].pass, "layers");
    EXPECT_EQ(renderer.last_stats().passes[5].pass, "tonemap");
    EXPECT_EQ(renderer.last_stats().layers, 0);  // no fog: the layer pass draws nothing
}

TEST_F(RendererGl, ExaggerationRaisesThePickedSurface)
{
    const kiri::geometry::Terrain hill = kiri::test::gaussian_hill();
    Renderer renderer;
    renderer.set_terrain(hill, 2.0);
    Camera top;
    top.position = {0.0, -1.0, 3000.0};
    top.target = {0.0, 0.0, 0.0};
    renderer.render(top, 101, 101);
    const auto peak = renderer.pick(50, 50);
    ASSERT_TRUE(peak.has_value());
    EXPECT_NEAR(peak->z, 600.0, 3.0);
}

// llvmpipe is deterministic: the same scene gives the same pixels, so a stored reference
// catches any change of shading or geometry. KIRI_UPDATE_REFERENCE=1 rewrites it.
TEST_F(RendererGl, GaussianHillMatchesReferenceImage)
{
    const kiri::geometry::Terrain hill = kiri::test::gaussian_hill();
    Renderer renderer;
    renderer.set_terrain(hill);
    kiri::render::SunLight sun;
    sun.direction = {0.6, -0.2, 0.5};
    renderer.set_sun(sun);
    const Image image = renderer.render(oblique_camera(), 160, 120);
    const std::filesystem::path reference =
        std::filesystem::path(KIRI_TESTS_DIR) / "render/reference/gaussian_hill.png";
    if (std::getenv("KIRI_UPDATE_REFERENCE"))
        kiri::render::write_png_atomic(reference, image);
    const Image expected = kiri::render::read_png(reference);
    ASSERT_EQ(expected.width, image.width);
    ASSERT_EQ(expected.height, image.height);
    double sum = 0.0;
    int large = 0;
    for (std::size_t k = 0; k < image.rgba.size(); ++k) {
        const int d = std::abs(int(image.rgba[k]) - int(expected.rgba[k]));
        sum += d;
        large += d > 8;
    }
    EXPECT_LE(sum / double(image.rgba.size()), 0.5);
    EXPECT_LE(large, int(image.rgba.size() / 200));
    // And it is a picture, not a blank: the hill's sunlit flank is lit differently from the
    // plain around it (the surround, flat to the horizon: measured 182 and 140 levels).
    const auto luminance = [&](int x, int y) {
        const std::uint8_t* p = &image.rgba[(std::size_t(y) * 160 + x) * 4];
        return 0.3 * p[0] + 0.59 * p[1] + 0.11 * p[2];
    };
    EXPECT_GT(std::abs(luminance(100, 55) - luminance(80, 110)), 30.0);
}

}  // namespace
