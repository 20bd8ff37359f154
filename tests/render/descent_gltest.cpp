// An eye that moves through the cloud without seams. The default scene in combined
// mode (froxels near, layers far, particles in the top band; docs/combined.md) along a camera
// path from far above, down through the top of the fog, into it and out below it; every frame
// against the CPU reference ray marcher of the same fog at low resolution. Label slow: the
// reference of each frame takes a second or two.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "kiri/geometry/reference/reference_fog.hpp"
#include "kiri/geometry/scene/scene.hpp"
#include "kiri/geometry/scene/pipeline.hpp"
#include "kiri/render/fog_error.hpp"
#include "kiri/render/scene_rendering.hpp"
#include "render/render_fixture.hpp"

namespace {

namespace g = kiri::geometry;
using namespace kiri::render;

double mean_luminance(const RadianceImage& image)
{
    double sum = 0.0;
    for (std::size_t k = 0; k < image.rgba.size(); k += 4)
        sum += g::luminance({image.rgba[k], image.rgba[k + 1], image.rgba[k + 2]});
    return sum / double(image.rgba.size() / 4);
}

// The reference's frame: its fog composed over the GPU's own background.
double mean_luminance(const g::ReferenceImage& ref, const RadianceImage& background)
{
    double sum = 0.0;
    for (std::size_t k = 0; k < ref.transmittance.size(); ++k) {
        const float* b = &background.rgba[4 * k];
        sum += g::luminance({b[0], b[1], b[2]}) * ref.transmittance[k] + g::luminance(ref.inscatter[k]);
    }
    return sum / double(ref.transmittance.size());
}

struct Frame {
    double height = 0.0;  // of the eye above the fog's bottom (m)
    const char* where = "";
    double error = 0.0;  // mean relative luminance error against the reference
    double p99 = 0.0;
    double y_gpu = 0.0, y_ref = 0.0;  // mean luminance of the frame and of the reference's
    int fog_pixels = 0;
};

class Descent : public kiri::test::GlTest {};

TEST_F(Descent, ThroughTheCloudWithoutPopsOrHollowness)
{
    g::Scene scene = g::load_scene(std::string(KIRI_DATA_DIR) + "/scenes/jacksboro.json");
    // Stills: without the temporal filter each frame is final at once (its convergence and
    // history rejection are FroxelGl's tests), so every frame is one draw.
    scene.froxel.temporal = false;
    const g::PipelineProducts fog = g::author_scene(scene, pipeline_target(FogMode::combined, scene));
    const g::Terrain& terrain = *fog.terrain;
    const g::Medium& medium = *fog.medium;
    // Over a valley south of the centre, looking north-east and down.
    const double x = -2000.0, y = -3000.0;
    const g::MediumColumn c = medium.column(x, y);
    ASSERT_GT(c.coverage, 0.5);
    ASSERT_GT(c.top - c.bottom, 100.0);
    const double ground = terrain.height(x, y);
    const double depth = c.top - c.bottom;
    std::printf("    the path at (%.0f, %.0f): ground %.1f m, fog from %.1f to %.1f m (world)\n", x, y, ground,
                c.bottom, c.top);
    std::vector<Frame> path = {
        {depth + 3000.0, "far above"}, {depth + 800.0, "above"},        {depth + 150.0, "just above"},
        {depth + 20.0, "touching"},    {depth - 20.0, "in the top"},    {0.6 * depth, "inside"},
        {0.3 * depth, "inside"},       {0.08 * depth, "near the base"},
    };
    if (c.bottom - ground > 30.0)
        path.push_back({-0.5 * (c.bottom - ground), "below"});

    const int width = 64, height = 36;
    const SunLight sun = to_sun(scene.sun);
    Renderer fogged, bare;
    for (Renderer* r : {&fogged, &bare}) {
        r->set_terrain(terrain);
        r->set_sun(sun);
    }
    const SceneRendering combined(scene, fog, FogMode::combined);
    combined.apply(fogged);
    const g::FroxelOptions& froxel = combined.froxel_options();
    const g::FogLighting light = scene_fog_lighting(scene, &medium, froxel);
    for (Frame& f : path) {
        Camera camera;
        camera.position = {x, y, c.bottom + f.height};
        camera.target = camera.position + glm::dvec3(2000.0, 2000.0, -900.0);
        camera.fov_y_deg = 60.0;
        const auto start = std::chrono::steady_clock::now();
        fogged.render(camera, width, height);  // a still picture
        const RadianceImage with_fog = fogged.read_radiance();
        bare.draw(camera, width, height);
        const RadianceImage without = bare.read_radiance();
        const double gl_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const g::ReferenceView view = reference_view(camera, width, height, froxel.far);
        const g::ReferenceImage ref =
            g::render_reference_fog({&medium, froxel.height_fog}, &terrain.heightfield(), view, light);
        const FogError e = compare_frames(with_fog, without, ref);
        f.error = e.mean_relative;
        f.p99 = e.p99_relative;
        f.fog_pixels = e.fog_pixels;
        f.y_gpu = mean_luminance(with_fog);
        f.y_ref = mean_luminance(ref, without);
        std::printf(
            "    %-14s eye %7.0f m above the base: fog pixels %4d, mean error %.3f, p99 %.3f, Y %.4f (reference "
            "%.4f, %.1f s; GL %.1f s)\n",
            f.where, f.height, f.fog_pixels, f.error, f.p99, f.y_gpu, f.y_ref, ref.seconds, gl_seconds);
    }
    for (std::size_t i = 0; i < path.size(); ++i) {
        const Frame& f = path[i];
        // The fog never vanishes: the reference sees it in most of the frame, and so does kiri.
        EXPECT_GT(f.fog_pixels, width * height / 5) << f.where;
        // Every frame, inside the cloud included (no hollow look), is close to the reference.
        EXPECT_LT(f.error, 0.12) << f.where;
        if (i == 0)
            continue;
        // No pop: the frame's brightness changes from one step to the next as the reference's
        // does, within a small part of the frame's brightness.
        const double change = f.y_gpu - path[i - 1].y_gpu, expected = f.y_ref - path[i - 1].y_ref;
        EXPECT_LT(std::abs(change - expected), 0.06 * f.y_ref) << path[i - 1].where << " -> " << f.where;
    }
}

}  // namespace
