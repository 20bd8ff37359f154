// What kiri-preview computes without a window: the background pipeline (only the stages whose
// inputs changed run again; a failed edit keeps the last good fog; the latest request wins),
// the views of the fitted surface, the camera, camera paths and saved scenes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <glm/geometric.hpp>

#include "camera_path.hpp"
#include "cli/kiri_runner.hpp"
#include "fog_views.hpp"
#include "geometry/fog_test_terrains.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/medium/fog_partition.hpp"
#include "kiri/geometry/scene/fog_spec.hpp"
#include "kiri/geometry/scene/scene_fog.hpp"
#include "kiri/geometry/terrain/terrain.hpp"
#include "orbit_camera.hpp"
#include "pipeline.hpp"
#include "scene_file.hpp"
#include "temp_path.hpp"

namespace fs = std::filesystem;
namespace g = kiri::geometry;
using kiri::preview::Pipeline;
using kiri::preview::Products;
using kiri::preview::Stage;

namespace {

// The default scene with big patches and a coarse tessellation: the same stages, faster.
g::Scene small_scene()
{
    g::Scene s = g::load_scene(fs::path(KIRI_DATA_DIR) / "scenes/jacksboro.json");
    s.fog->patch_size = 3000.0;
    s.fog->tessellation.level = 4;
    return s;
}

Products run(Pipeline& p, const g::Scene& s)
{
    p.request(s);
    p.wait_idle();
    std::optional<Products> r = p.take();
    EXPECT_TRUE(r.has_value());
    return r ? std::move(*r) : Products{};
}

double mean_height(const kiri::preview::FogProducts& fog)
{
    double sum = 0.0;
    for (const glm::vec3& q : fog.views->surface.positions)
        sum += q.z;
    return sum / double(fog.views->surface.positions.size());
}

int runs(const Pipeline& p, Stage stage) { return p.status().stages[std::size_t(stage)].runs; }

// Runs per stage so far: terrain, control mesh, fit, tessellation, layer base, views.
std::array<int, 6> runs(const Pipeline& p)
{
    std::array<int, 6> out{};
    int i = 0;
    for (Stage stage :
         {Stage::terrain, Stage::control_mesh, Stage::fit, Stage::tessellation, Stage::layer_base, Stage::views})
        out[std::size_t(i++)] = runs(p, stage);
    return out;
}

// Runs of the stages after the views: placement, medium, particles.
std::array<int, 3> fog_runs(const Pipeline& p)
{
    return {runs(p, Stage::placement), runs(p, Stage::medium), runs(p, Stage::particles)};
}

Products run(Pipeline& p, const g::Scene& s, kiri::preview::Needs needs)
{
    p.request(s, needs);
    p.wait_idle();
    std::optional<Products> r = p.take();
    EXPECT_TRUE(r.has_value());
    return r ? std::move(*r) : Products{};
}

}  // namespace

TEST(PreviewPipeline, RecomputesOnlyTheStagesWhoseInputsChanged)
{
    Pipeline p;
    g::Scene s = small_scene();
    const Products first = run(p, s);
    ASSERT_TRUE(first.error.empty()) << first.error;
    ASSERT_TRUE(first.terrain && first.fog);
    EXPECT_EQ(runs(p), (std::array<int, 6>{1, 1, 1, 1, 1, 1}));

    // Sun and the layers' look apply per frame: nothing runs, the same products come back.
    s.sun.intensity = 1.0;
    s.layers.opacity = 0.3;
    s.cameras.pop_back();
    const Products same = run(p, s);
    EXPECT_EQ(runs(p), (std::array<int, 6>{1, 1, 1, 1, 1, 1}));
    EXPECT_EQ(same.terrain, first.terrain);
    EXPECT_EQ(same.fog, first.fog);

    // Tessellation: the fitted surface is kept; (6/4)^2 as many triangles.
    s.fog->tessellation.level = 6;
    const Products finer = run(p, s);
    EXPECT_EQ(runs(p), (std::array<int, 6>{1, 1, 1, 2, 2, 2}));
    EXPECT_EQ(finer.fog->triangles * 16, first.fog->triangles * 36);
    EXPECT_EQ(finer.fog->fit.rms_deviation, first.fog->fit.rms_deviation);

    // A fit option refits the same control mesh.
    s.fog->fit.offset = 120.0;
    const Products refit = run(p, s);
    EXPECT_EQ(runs(p), (std::array<int, 6>{1, 1, 2, 3, 3, 3}));
    EXPECT_EQ(refit.fog->patches, first.fog->patches);
    // The refit (same control mesh, samples reused) is the fit `kiri author` makes from scratch.
    const g::AuthoredSurface direct = g::author_base_surface(*refit.terrain, g::world_fog_spec(s));
    EXPECT_NEAR(refit.fog->fit.rms_deviation, direct.fit.rms_deviation, 1e-9 * direct.fit.rms_deviation);
    EXPECT_NEAR(refit.fog->fit.max_deviation, direct.fit.max_deviation, 1e-9 * direct.fit.max_deviation);
    EXPECT_NEAR(refit.fog->fit.min_clearance, direct.fit.min_clearance, 1e-9);
    EXPECT_GT(mean_height(*refit.fog), mean_height(*finer.fog));

    // The layer texture only rebuilds the layer base.
    s.layers.texture.fade_width = 0.25;
    const Products texture = run(p, s);
    EXPECT_EQ(runs(p), (std::array<int, 6>{1, 1, 2, 3, 4, 3}));
    EXPECT_EQ(texture.fog->views, refit.fog->views);
    EXPECT_NE(texture.fog->base, refit.fog->base);

    // The footprint rebuilds the control mesh and what follows.
    s.fog->margin = 4000.0;
    const Products smaller = run(p, s);
    EXPECT_EQ(runs(p), (std::array<int, 6>{1, 2, 3, 4, 5, 4}));
    EXPECT_LT(smaller.fog->patches, refit.fog->patches);

    // The exaggeration reloads the terrain and everything on it.
    s.terrain.exaggeration = 2.0;
    const Products steeper = run(p, s);
    EXPECT_EQ(runs(p), (std::array<int, 6>{2, 3, 4, 5, 6, 5}));
    EXPECT_NEAR(steeper.terrain->bounds().max.z / smaller.terrain->bounds().max.z, 2.0 / 1.5, 1e-12);
    EXPECT_TRUE(steeper.error.empty()) << steeper.error;
}

TEST(PreviewPipeline, FogPlacedByTheTerrainIsWhatKiriAuthorMakes)
{
    Pipeline p;
    g::Scene s = g::load_scene(fs::path(KIRI_DATA_DIR) / "scenes/jacksboro_fill.json");
    ASSERT_TRUE(s.fog && s.fog->placement);
    const Products first = run(p, s, {.medium = true});
    ASSERT_TRUE(first.error.empty()) << first.error;
    ASSERT_TRUE(first.fog && first.fog->placed && first.medium);
    EXPECT_EQ(fog_runs(p), (std::array<int, 3>{1, 1, 0}));
    EXPECT_EQ(first.particles, nullptr);  // not asked for

    // The same placement, lake fit, layer stack and medium as `kiri author` (author_scene_fog).
    const g::SceneFog direct = g::author_scene_fog(s, *first.terrain);
    ASSERT_TRUE(direct.placed);
    EXPECT_EQ(first.fog->placed->figures.cells, direct.placed->figures.cells);
    EXPECT_DOUBLE_EQ(first.fog->placed->figures.volume_m3, direct.placed->figures.volume_m3);
    EXPECT_DOUBLE_EQ(first.fog->placed_thickness, direct.layers.thickness);
    EXPECT_DOUBLE_EQ(first.fog->base_offset, direct.layers.base_offset);
    EXPECT_EQ(first.fog->triangles, direct.authored.tessellation.mesh.n_faces());
    EXPECT_NEAR(first.fog->fit.rms_deviation, direct.authored.fit.rms_deviation,
                1e-9 * (1.0 + direct.authored.fit.rms_deviation));
    EXPECT_EQ(first.medium->grid().nx, direct.medium.grid().nx);
    EXPECT_NEAR(first.medium->shell_volume(), direct.medium.shell_volume(), 1e-9 * direct.medium.shell_volume());

    // A tessellation edit keeps the placement and the medium; the medium's optics only remake it.
    s.fog->tessellation.level = 6;
    run(p, s, {.medium = true});
    EXPECT_EQ(fog_runs(p), (std::array<int, 3>{1, 2, 0}));  // the layer base changed under it
    s.medium.albedo = 0.9;
    const Products albedo = run(p, s, {.medium = true});
    EXPECT_EQ(fog_runs(p), (std::array<int, 3>{1, 3, 0}));
    EXPECT_DOUBLE_EQ(albedo.medium->options().albedo, 0.9);

    // A higher fog top places the fog again: more of it, deeper, and everything after reruns.
    const std::array<int, 6> before = runs(p);
    s.fog->placement->regions.at(0).top += 40.0;
    const Products higher = run(p, s, {.medium = true});
    ASSERT_TRUE(higher.error.empty()) << higher.error;
    EXPECT_EQ(fog_runs(p), (std::array<int, 3>{2, 4, 0}));
    EXPECT_EQ(runs(p)[1], before[1] + 1);  // control mesh
    EXPECT_GT(higher.fog->placed->figures.volume_m3, first.fog->placed->figures.volume_m3);
    EXPECT_NEAR(higher.fog->placed_thickness, first.fog->placed_thickness + 40.0 * s.terrain.exaggeration, 1e-6);
}

TEST(PreviewPipeline, TheParticleCountResamplesOnlyTheParticles)
{
    Pipeline p;
    g::Scene s = small_scene();
    s.particles.count = 3000;
    const Products first = run(p, s, {.medium = true, .particles = true});
    ASSERT_TRUE(first.error.empty()) << first.error;
    ASSERT_TRUE(first.particles && first.medium);
    EXPECT_EQ(first.particles->particles.size(), 3000u);
    EXPECT_EQ(fog_runs(p), (std::array<int, 3>{0, 1, 1}));
    // The particles `kiri author` samples from the same scene, bit for bit.
    const g::SceneFog direct = g::author_scene_fog(s, *first.terrain);
    const g::ParticleCloud cloud = g::sample_particles(direct.medium, s.particles);
    ASSERT_EQ(cloud.particles.size(), first.particles->particles.size());
    EXPECT_EQ(cloud.particles[1234].position, first.particles->particles[1234].position);
    EXPECT_EQ(cloud.particles[1234].optical_depth, first.particles->particles[1234].optical_depth);

    s.particles.count = 4000;
    const Products more = run(p, s, {.medium = true, .particles = true});
    EXPECT_EQ(runs(p), (std::array<int, 6>{1, 1, 1, 1, 1, 1}));
    EXPECT_EQ(fog_runs(p), (std::array<int, 3>{0, 1, 2}));
    EXPECT_EQ(more.medium, first.medium);
    EXPECT_EQ(more.particles->particles.size(), 4000u);

    // The attenuation buffer's options apply per frame: nothing is resampled.
    s.particles.resolution = 256;
    s.particles.half_float = false;
    const Products finer = run(p, s, {.medium = true, .particles = true});
    EXPECT_EQ(fog_runs(p), (std::array<int, 3>{0, 1, 2}));
    EXPECT_EQ(finer.particles, more.particles);

    // A mode without particles gets none and runs nothing; back to particles, the same ones.
    const Products layers = run(p, s, {});
    EXPECT_EQ(layers.particles, nullptr);
    EXPECT_EQ(layers.medium, nullptr);
    const Products again = run(p, s, {.medium = true, .particles = true});
    EXPECT_EQ(fog_runs(p), (std::array<int, 3>{0, 1, 2}));
    EXPECT_EQ(again.particles, more.particles);

    // Combined: the particles stand for the top band's share of the medium (as SceneRendering
    // samples them); a zero share gives none.
    const Products shared = run(p, s, {.medium = true, .particles = true, .particle_share = true});
    EXPECT_EQ(fog_runs(p), (std::array<int, 3>{0, 1, 3}));
    ASSERT_TRUE(shared.particles);
    const g::Medium& m = *shared.medium;
    const g::ParticleCloud top = g::sample_particles(
        m, s.particles, {}, [&](const glm::dvec3& q) { return g::particle_share(s.combined, m.height_fraction(q)); });
    ASSERT_EQ(top.particles.size(), shared.particles->particles.size());
    EXPECT_EQ(top.particles[77].position, shared.particles->particles[77].position);
    EXPECT_NE(top.particles[77].position, more.particles->particles[77].position);
    s.combined.particle_share = 0.0;
    const Products none = run(p, s, {.medium = true, .particles = true, .particle_share = true});
    EXPECT_EQ(none.particles, nullptr);
    EXPECT_TRUE(none.error.empty()) << none.error;
}

TEST(PreviewPipeline, AFailedEditKeepsTheLastGoodFogAndNamesTheProblem)
{
    Pipeline p;
    g::Scene s = small_scene();
    const Products good = run(p, s);
    ASSERT_TRUE(good.fog);
    s.fog->fit.mode = g::FitMode::lake;
    s.fog->fit.altitude = 100.0;  // below the lowest ground (236 m)
    const Products bad = run(p, s);
    EXPECT_NE(bad.error.find("fit: "), std::string::npos) << bad.error;
    EXPECT_NE(bad.error.find("/fog"), std::string::npos) << bad.error;
    EXPECT_EQ(bad.fog, good.fog);
    EXPECT_EQ(bad.terrain, good.terrain);
    s.fog->fit.altitude = 500.0;
    const Products fixed = run(p, s);
    EXPECT_TRUE(fixed.error.empty()) << fixed.error;
    ASSERT_TRUE(fixed.fog);
    EXPECT_NE(fixed.fog, good.fog);
    // A lake's layers hang one thickness below its top.
    EXPECT_DOUBLE_EQ(fixed.fog->base_offset, -s.fog->fit.thickness * s.terrain.exaggeration);
}

TEST(PreviewPipeline, TheLatestRequestWins)
{
    Pipeline p;
    g::Scene s = small_scene();
    for (int level : {2, 3, 5}) {
        s.fog->tessellation.level = level;
        p.request(s);
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
