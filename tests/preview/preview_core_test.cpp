// What kiri-preview computes without a window: the background pipeline (only the stages whose
// inputs changed run again; a failed edit keeps the last good fog; the latest request wins),
// the views of the fitted surface, the camera, camera paths and saved scenes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include <glm/geometric.hpp>

#include "camera_path.hpp"
#include "frame_budget.hpp"
#include "mouse_drags.hpp"
#include "cli/kiri_runner.hpp"
#include "fog_views.hpp"
#include "geometry/fog_test_terrains.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/medium/fog_partition.hpp"
#include "kiri/geometry/scene/fog_spec.hpp"
#include "kiri/geometry/scene/pipeline.hpp"
#include "kiri/geometry/terrain/terrain.hpp"
#include "orbit_camera.hpp"
#include "pipeline.hpp"
#include "scene_file.hpp"
#include "temp_path.hpp"

namespace fs = std::filesystem;
namespace g = kiri::geometry;
using kiri::preview::Pipeline;
using kiri::preview::Products;

namespace {

// The default scene with big patches and a coarse tessellation: the same stages, faster.
g::Scene small_scene()
{
    g::Scene s = g::load_scene(fs::path(KIRI_DATA_DIR) / "scenes/jacksboro.json");
    s.fog->patch_size = 3000.0;
    s.fog->tessellation.level = 4;
    return s;
}

Products run(Pipeline& p, const g::Scene& s, const g::PipelineTarget& target = {})
{
    p.request(s, target);
    p.wait_idle();
    std::optional<Products> r = p.take();
    EXPECT_TRUE(r.has_value());
    return r ? std::move(*r) : Products{};
}

int runs(const Pipeline& p, int stage) { return p.status().stages[std::size_t(stage)].runs; }
int runs(const Pipeline& p, g::Stage stage) { return runs(p, int(stage)); }

}  // namespace

// The authoring pipeline's own recomputation is tested in tests/geometry/pipeline_test.cpp; here
// the preview's thread around it: its counts, its views, its errors and its queue.
TEST(PreviewPipeline, CountsTheStagesItRanAndRemakesTheViewsWithTheTessellation)
{
    Pipeline p;
    g::Scene s = small_scene();
    const Products first = run(p, s);
    ASSERT_TRUE(first.error.empty()) << first.error;
    ASSERT_TRUE(first.fog.has_fog() && first.views);
    EXPECT_EQ(runs(p, g::Stage::fit), 1);
    EXPECT_EQ(runs(p, kiri::preview::views_stage), 1);
    EXPECT_TRUE(first.rebuilt[std::size_t(g::Stage::fit)]);
    EXPECT_EQ(first.views->surface.positions.size(), first.fog.tessellation->mesh.n_vertices());

    // A per-frame edit runs nothing and keeps the views.
    s.layers.opacity = 0.3;
    const Products same = run(p, s);
    EXPECT_EQ(runs(p, g::Stage::fit), 1);
    EXPECT_EQ(runs(p, kiri::preview::views_stage), 1);
    EXPECT_EQ(same.views, first.views);
    EXPECT_FALSE(same.rebuilt[std::size_t(g::Stage::fit)]);

    // The layer texture: a new layer base over the same surface, the same views.
    s.layers.texture.fade_width = 0.25;
    const Products texture = run(p, s);
    EXPECT_EQ(runs(p, g::Stage::layer_base), 2);
    EXPECT_EQ(runs(p, kiri::preview::views_stage), 1);
    EXPECT_EQ(texture.views, first.views);

    // A new tessellation: new views of it.
    s.fog->tessellation.level = 6;
    const Products finer = run(p, s);
    EXPECT_EQ(runs(p, g::Stage::tessellation), 2);
    EXPECT_EQ(runs(p, kiri::preview::views_stage), 2);
    EXPECT_NE(finer.views, first.views);
    EXPECT_EQ(finer.views->surface.positions.size(), finer.fog.tessellation->mesh.n_vertices());
    EXPECT_STREQ(kiri::preview::stage_name(kiri::preview::views_stage), "views");
    EXPECT_STREQ(kiri::preview::stage_name(int(g::Stage::control_mesh)), "control mesh");
}

TEST(PreviewPipeline, AFailedEditKeepsTheLastGoodFogAndNamesTheProblem)
{
    Pipeline p;
    g::Scene s = small_scene();
    const Products good = run(p, s);
    ASSERT_TRUE(good.fog.has_fog());
    s.fog->fit.mode = g::FitMode::lake;
    s.fog->fit.altitude = 100.0;  // below the lowest ground (236 m)
    const Products bad = run(p, s);
    EXPECT_NE(bad.error.find("fit: "), std::string::npos) << bad.error;
    EXPECT_NE(bad.error.find("/fog"), std::string::npos) << bad.error;
    EXPECT_EQ(bad.fog.layer_base, good.fog.layer_base);
    EXPECT_EQ(bad.fog.terrain, good.fog.terrain);
    EXPECT_EQ(bad.views, good.views);
    s.fog->fit.altitude = 500.0;
    const Products fixed = run(p, s);
    EXPECT_TRUE(fixed.error.empty()) << fixed.error;
    EXPECT_NE(fixed.fog.layer_base, good.fog.layer_base);
}

TEST(PreviewPipeline, TheModesTargetGivesTheMediumAndParticlesOnlyWhenAskedFor)
{
    Pipeline p;
    g::Scene s = small_scene();
    s.particles.count = 2000;
    const Products layers = run(p, s);
    EXPECT_EQ(layers.fog.medium, nullptr);
    EXPECT_EQ(layers.fog.particles, nullptr);
    EXPECT_EQ(runs(p, g::Stage::medium), 0);
    const Products particles = run(p, s, {g::Stage::particles, g::ParticleSet::whole});
    ASSERT_TRUE(particles.fog.medium && particles.fog.particles);
    EXPECT_EQ(particles.fog.particles->particles.size(), 2000u);
    EXPECT_EQ(runs(p, g::Stage::medium), 1);
    EXPECT_EQ(runs(p, g::Stage::particles), 1);
}

TEST(PreviewPipeline, TheLatestRequestWins)
{
    Pipeline p;
    g::Scene s = small_scene();
    for (int level : {2, 3, 5}) {
        s.fog->tessellation.level = level;
        p.request(s, {});
    }
    p.wait_idle();
    const std::optional<Products> last = p.take();
    ASSERT_TRUE(last);
    EXPECT_EQ(last->generation, 3u);
    EXPECT_EQ(last->scene.fog->tessellation.level, 5);
    EXPECT_EQ(p.status().finished, p.status().requested);
    EXPECT_FALSE(p.status().busy);
    EXPECT_FALSE(p.take().has_value());  // taken once
}

TEST(FogViews, FlatBlanketHasNoDeviationAndItsOffsetAsClearance)
{
    // A plane is fitted exactly: the surface is the terrain + offset everywhere.
    const g::Terrain flat(
        kiri::test::make_heightfield(41, 41, 50.0, -1000.0, -1000.0, [](double, double) { return 100.0; }));
    g::FogSpec spec;
    spec.patch_size = 500.0;
    spec.margin = 100.0;
    spec.fit.offset = 50.0;
    spec.tessellation.level = 3;
    g::BaseSurface surface = g::fog_control_surface(flat, spec);
    g::fit_fog_surface(surface, flat, spec);
    const g::Tessellation t = g::tessellate(surface, spec.tessellation);
    const auto views = kiri::preview::make_fog_views(surface, t, flat, spec.fit);
    EXPECT_LT(views->deviation_range, 1e-6);
    EXPECT_NEAR(views->clearance_range, 50.0, 1e-6);
    ASSERT_EQ(views->surface.positions.size(), t.mesh.n_vertices());
    EXPECT_EQ(views->surface.indices.size(), 3 * t.mesh.n_faces());
    for (const glm::vec4& c : views->deviation_colors)  // zero deviation is white
        EXPECT_GT(std::min({c.r, c.g, c.b}), 0.95f);
    const int patches = surface.num_patches();
    EXPECT_EQ(views->patch_borders.indices.size(), std::size_t(patches) * 4 * 16 * 2);
    for (const glm::vec3& q : views->patch_borders.positions)
        EXPECT_NEAR(q.z, 150.0, 1e-3);
    EXPECT_EQ(views->control_mesh.indices.size(), 2 * surface.control().mesh.n_edges());
}

TEST(FogViews, ColourMapsRunBlueWhiteRedAndDarkToYellow)
{
    const glm::vec4 lo = kiri::preview::diverging_color(-1.0), mid = kiri::preview::diverging_color(0.0),
                    hi = kiri::preview::diverging_color(1.0);
    EXPECT_GT(lo.b, lo.r + 0.5f);
    EXPECT_GT(hi.r, hi.b + 0.5f);
    EXPECT_GT(std::min({mid.r, mid.g, mid.b}), 0.95f);
    EXPECT_EQ(kiri::preview::diverging_color(5.0), hi);  // saturates
    const glm::vec4 dark = kiri::preview::sequential_color(0.0), bright = kiri::preview::sequential_color(1.0);
    EXPECT_LT(dark.r + dark.g + dark.b, 0.7f);
    EXPECT_GT(bright.r + bright.g, 1.8f);
    EXPECT_EQ(kiri::preview::sequential_color(std::nan("")), dark);
}

TEST(OrbitCamera, MovesAsItsControlsSay)
{
    kiri::preview::OrbitCamera c;
    const glm::dvec3 eye(-3000.0, -4000.0, 2000.0), target(100.0, 200.0, 300.0);
    c.look(eye, target, 40.0);
    EXPECT_LT(glm::length(c.camera().position - eye), 1e-9);
    EXPECT_EQ(c.camera().target, target);
    const double d = glm::length(eye - target);
    c.orbit(120.0, -40.0);  // about the target: same distance
    EXPECT_EQ(c.target(), target);
    EXPECT_NEAR(glm::length(c.eye() - target), d, 1e-9);
    const glm::dvec3 e = c.eye();
    c.look_around(-50.0, 30.0);  // about the eye
    EXPECT_LT(glm::length(c.eye() - e), 1e-9);
    // Pan: 100 pixels of a 500-pixel viewport move the target by 100 / 500 of the view's height
    // at the target's distance, across the line of sight.
    const glm::dvec3 before = c.target(), forward = glm::normalize(c.target() - c.eye());
    c.pan(100.0, 0.0, 500.0);
    const glm::dvec3 moved = c.target() - before;
    EXPECT_NEAR(glm::length(moved), 100.0 / 500.0 * 2.0 * d * std::tan(20.0 * M_PI / 180.0), 1e-6);
    EXPECT_NEAR(glm::dot(moved, forward), 0.0, 1e-9);
    c.zoom(1.0);
    EXPECT_NEAR(c.distance(), 0.85 * d, 1e-9);
    const glm::dvec3 eye_now = c.eye();
    c.set_target({0.0, 0.0, 0.0});  // a new pivot: the eye stays
    EXPECT_LT(glm::length(c.eye() - eye_now), 1e-9);
    c.fly(1.0, 0.0, 0.0, 2.0, 10.0);  // 20 m forward
    EXPECT_NEAR(glm::length(c.eye() - eye_now), 20.0, 1e-9);
}

// A drag gathers the cursor's steps while its button is down, whatever the frames: a press, moves
// and a release between two frames give the whole drag at the next; the cursor's way to the
// press is not part of it, nor a drag begun on the panel.
TEST(MouseDrags, GatherTheStepsBetweenPressAndReleaseWhateverTheFrames)
{
    kiri::preview::MouseDrags d;
    d.move(40.0, 300.0);
    d.move(150.0, 250.0);  // to the press: no button down
    d.press(1, false);
    for (int i = 1; i <= 10; ++i)
        d.move(150.0, 250.0 + 8.0 * i);
    EXPECT_TRUE(d.held(1));
    d.release(1);
    EXPECT_FALSE(d.held(1));
    d.move(40.0, 300.0);  // after the release
    EXPECT_EQ(d.take(1), glm::dvec2(0.0, 80.0));
    EXPECT_EQ(d.take(1), glm::dvec2(0.0));  // taken once
    EXPECT_EQ(d.take(0), glm::dvec2(0.0));  // the other buttons gathered nothing
    // Split across frames: each take has the steps since the last, and they add up.
    d.press(0, false);
    d.move(50.0, 310.0);
    const glm::dvec2 first = d.take(0);
    d.move(70.0, 290.0);
    d.release(0);
    EXPECT_EQ(first, glm::dvec2(10.0, 10.0));
    EXPECT_EQ(d.take(0), glm::dvec2(20.0, -20.0));
    // Begun on the panel: the camera gets nothing until the button comes up and goes down again.
    d.press(2, true);
    d.move(500.0, 100.0);
    EXPECT_FALSE(d.held(2));
    d.release(2);
    EXPECT_EQ(d.take(2), glm::dvec2(0.0));
    // Buttons GLFW has beyond the three are ignored.
    d.press(7, false);
    d.move(0.0, 0.0);
    EXPECT_EQ(d.take(7), glm::dvec2(0.0));
}

TEST(CameraPath, ReadsKeysAndInterpolates)
{
    const fs::path file = kiri::test::temp_path("path.txt");
    {
        std::ofstream out(file);
        out << "# a path\n0 0 100  0 10 0\n\n  100 0 300   0 10 0 60\n";
    }
    const auto keys = kiri::preview::load_camera_path(file);
    ASSERT_EQ(keys.size(), 2u);
    EXPECT_EQ(keys[0].fov_y_deg, 45.0);
    const kiri::render::Camera mid = kiri::preview::camera_on_path(keys, 0.5);
    EXPECT_EQ(mid.position, glm::dvec3(50.0, 0.0, 200.0));
    EXPECT_EQ(mid.fov_y_deg, 52.5);
    EXPECT_EQ(kiri::preview::camera_on_path(keys, 7.0).position, keys[1].position);
    const auto refused = [&](const std::string& text, const std::string& where) {
        std::ofstream(file) << text;
        try {
            kiri::preview::load_camera_path(file);
        } catch (const kiri::InputError& e) {
            EXPECT_EQ(e.field(), where) << text;
            return;
        }
        ADD_FAILURE() << "accepted: " << text;
    };
    refused("0 0 1 0 1 0\n0 0 1 0 1\n", "line 2");
    refused("0 0 1 0 1 0 200\n", "line 1");
    refused("0 0 1 0 0 1\n", "line 1");
    refused("0 0 1 0 1 0 45 x\n", "line 1");
    refused("# nothing\n", "");
    fs::remove(file);
}

TEST(SaveScene, WritesTheTerrainRelativeAndLoadsBackEqual)
{
    const g::Scene scene = g::load_scene(fs::absolute(fs::path(KIRI_DATA_DIR) / "scenes/jacksboro.json"));
    const fs::path dir = kiri::test::temp_path("save_scene") / "deeper";
    fs::create_directories(dir);
    kiri::preview::save_scene(scene, dir / "edited.json");
    const std::string text = kiri::test::read_all(dir / "edited.json");
    EXPECT_NE(text.find("\"path\": \"../"), std::string::npos) << "relative terrain path";
    g::Scene back = g::load_scene(dir / "edited.json");
    EXPECT_EQ(fs::weakly_canonical(back.terrain.path), fs::weakly_canonical(scene.terrain.path));
    g::Scene a = scene;
    back.file = a.file = fs::path();
    back.terrain.path = a.terrain.path = fs::path();
    EXPECT_EQ(g::scene_to_json(back), g::scene_to_json(a));
    EXPECT_FALSE(fs::exists(dir / "edited.json.tmp"));
    EXPECT_EQ(kiri::preview::next_screenshot_path(dir, "s"), dir / "s-preview-1.png");
    std::ofstream(dir / "s-preview-1.png") << "x";
    EXPECT_EQ(kiri::preview::next_screenshot_path(dir, "s"), dir / "s-preview-2.png");
    fs::remove_all(dir.parent_path());
}

// Dynamic resolution (frame_budget.hpp): the step is sqrt(target / measured), the exact scale
// for a frame whose whole cost is per pixel, damped to [0.7, 1.25] a frame.
TEST(FrameBudget, TheReducedResolutionStepsByPowersOfTwo)
{
    using kiri::preview::resolution_step;
    EXPECT_EQ(resolution_step(1.0f), 1.0);
    EXPECT_EQ(resolution_step(0.99f), 0.5);
    EXPECT_EQ(resolution_step(0.5f), 0.5);
    EXPECT_EQ(resolution_step(0.3f), 0.25);
    EXPECT_EQ(resolution_step(0.125f), 0.125);
    EXPECT_EQ(resolution_step(0.01f), 0.125);  // never coarser than an eighth
    EXPECT_EQ(resolution_step(4.0f), 1.0);
    EXPECT_EQ(resolution_step(std::nanf("")), 0.125);
    EXPECT_EQ(resolution_step(-1.0f), 0.125);
}

TEST(FrameBudget, AMovingFramesSidesAreNoPowersOfTwo)
{
    using kiri::preview::off_power_of_two;
    EXPECT_EQ(off_power_of_two(250), 257);  // a 16th of 241..256 is 16: 257, 129, 65, 33, 17
    EXPECT_EQ(off_power_of_two(141), 141);
    EXPECT_EQ(off_power_of_two(117), 129);  // a 16th of 113..128 is 8
    EXPECT_EQ(off_power_of_two(211), 211);
    EXPECT_EQ(off_power_of_two(1), 1);
    EXPECT_EQ(off_power_of_two(0), 0);
    EXPECT_EQ(off_power_of_two(std::numeric_limits<int>::max()), std::numeric_limits<int>::max());
    const auto power_of_two = [](int v) { return v >= 2 && (v & (v - 1)) == 0; };
    for (int side = 2; side <= 4096; ++side) {
        const int s = off_power_of_two(side);
        ASSERT_GE(s, side);
        ASSERT_LE(s - side, side > 32 ? 16 : 31) << side;
        for (int k = 1; k <= 16; k *= 2)
            ASSERT_FALSE(power_of_two((s + k - 1) / k)) << side << " -> " << s << " over " << k;
        if (s > side) {  // the next such size: every size between clashes
            ASSERT_EQ(off_power_of_two(s - 1), s);
        }
    }
}

TEST(FrameBudget, StepsTowardsTheBudgetDampedAndClamped)
{
    using kiri::preview::FrameBudget;
    using kiri::preview::next_moving_scale;
    const FrameBudget budget{100.0, 0.125f, 1.0f};
    // Within the damping: 400 ms at 0.8 -> 0.8 sqrt(100 / 400) = 0.4 is below 0.7 x 0.8.
    EXPECT_FLOAT_EQ(next_moving_scale(0.8f, 400.0, budget), 0.56f);
    EXPECT_FLOAT_EQ(next_moving_scale(0.5f, 156.25, budget), 0.4f);  // sqrt(0.64) = 0.8
    EXPECT_FLOAT_EQ(next_moving_scale(0.5f, 100.0, budget), 0.5f);   // on budget: stays
    EXPECT_FLOAT_EQ(next_moving_scale(0.4f, 81.0, budget), 0.4f * 10.0f / 9.0f);
    EXPECT_FLOAT_EQ(next_moving_scale(0.4f, 1.0, budget), 0.5f);  // 1.25 at most
    // A frame whose cost is all per pixel reaches its budget and stays there.
    float s = 1.0f;
    for (int i = 0; i < 20; ++i)
        s = next_moving_scale(s, 400.0 * double(s) * double(s), budget);
    EXPECT_NEAR(s, 0.5f, 1e-4f);
    // The range: never below min_scale nor above max_scale.
    EXPECT_FLOAT_EQ(next_moving_scale(0.13f, 1e6, budget), 0.125f);
    EXPECT_FLOAT_EQ(next_moving_scale(0.95f, 1.0, FrameBudget{100.0, 0.125f, 0.9f}), 0.9f);
    // Nothing measured, or nonsense: the last scale, within the range.
    EXPECT_FLOAT_EQ(next_moving_scale(0.3f, 0.0, budget), 0.3f);
    EXPECT_FLOAT_EQ(next_moving_scale(0.3f, std::nan(""), budget), 0.3f);
    EXPECT_FLOAT_EQ(next_moving_scale(0.3f, 50.0, FrameBudget{std::numeric_limits<double>::infinity(), 0.125f, 1.0f}),
                    0.3f);
    EXPECT_FLOAT_EQ(next_moving_scale(std::nanf(""), 50.0, budget), 1.0f);  // from the top
    EXPECT_FLOAT_EQ(next_moving_scale(5.0f, 100.0, budget), 1.0f);
    EXPECT_FLOAT_EQ(next_moving_scale(0.5f, 100.0, FrameBudget{100.0, std::nanf(""), 0.1f}), 0.125f);
}
