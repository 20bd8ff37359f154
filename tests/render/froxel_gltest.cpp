// The froxel fog against the CPU reference ray marcher (geometry/reference_fog.hpp) at small
// resolution: homogeneous fog, height fog (a dense haze from above too), a 2 m layer at 30 m (the Jacksboro fog lake is in
// froxel_lake_gltest.cpp); and what the pass must not do: NaN, g at +-1, work it need not do,
// and what it must: rerun when any option changes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <optional>
#include <utility>

#include <glm/geometric.hpp>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/medium/fog_partition.hpp"
#include "render/froxel_fixture.hpp"

namespace {

using namespace kiri::test;

TEST_F(FroxelGl, HomogeneousFog)
{
    const g::Terrain ground = flat_ground();
    const g::Medium fog = slab(0.0, 1500.0, 0.003);
    Camera c;
    c.position = {0.0, -1800.0, 60.0};
    c.target = {0.0, 0.0, 0.0};
    const Compared r = compare(ground, &fog, small(24, 14), c, 96, 54);
    EXPECT_GT(r.error.fog_pixels, 96 * 54 / 2);
    EXPECT_LT(r.error.mean_relative, 0.02);
    EXPECT_LT(r.error.p99_relative, 0.06);
}

TEST_F(FroxelGl, AReducedResolutionKeepsThePixelsPerTile)
{
    // The preview while the view moves: the frame at half its size and the volume at half its
    // tiles across and down (Renderer::set_froxel_resolution), so a tile still spans the still's
    // 4 x 4 pixels, and the picture as close to the reference as the still at that size.
    const g::Terrain ground = flat_ground();
    const g::Medium fog = slab(0.0, 1500.0, 0.003);
    Camera c;
    c.position = {0.0, -1800.0, 60.0};
    c.target = {0.0, 0.0, 0.0};
    const g::FroxelOptions o = small(24, 14);
    const SunLight light = sun();
    Renderer r;
    r.set_terrain(ground);
    SunLight shadowed = light;
    shadowed.terrain_shadows = o.terrain_shadows;
    r.set_sun(shadowed);
    r.set_froxel_fog(&fog, o);
    r.set_froxel_resolution(0.5);
    r.render(c, 48, 27);
    EXPECT_EQ(r.last_stats().froxel.size, glm::ivec3(12, 7, o.slices));
    const g::ReferenceImage truth =
        g::render_reference_fog({&fog, o.height_fog}, &ground.heightfield(),
                                kiri::render::reference_view(c, 48, 27, o.far), lighting(light, o, &fog, ground));
    const kiri::render::FogError e = kiri::render::compare_fog(r.read_froxel_fog(), truth);
    std::printf("    half the tiles at half the size: mean %.4f, p99 %.4f\n", e.mean_relative, e.p99_relative);
    EXPECT_GT(e.fog_pixels, 48 * 27 / 2);
    EXPECT_LT(e.mean_relative, 0.02);
    EXPECT_LT(e.p99_relative, 0.06);
    // Back to the whole volume: rebuilt at the options' size.
    r.set_froxel_resolution(1.0);
    r.render(c, 96, 54);
    EXPECT_EQ(r.last_stats().froxel.size, glm::ivec3(24, 14, o.slices));
}

TEST_F(FroxelGl, HeightFog)
{
    const g::Terrain ground = flat_ground();
    g::FroxelOptions o = small(24, 14);
    o.height_fog.extinction = 0.004;
    o.height_fog.base = 0.0;
    o.height_fog.scale_height = 40.0;
    o.height_fog.anisotropy = 0.5;
    Camera c;
    c.position = {0.0, -1800.0, 100.0};
    c.target = {0.0, 0.0, 0.0};
    const Compared r = compare(ground, nullptr, o, c, 96, 54);
    EXPECT_GT(r.error.fog_pixels, 96 * 54 / 2);
    EXPECT_LT(r.error.mean_relative, 0.02);
    // The worst pixels are sky just above the horizon, where the fog changes fastest from one
    // row to the next: 4 pixels a tile blur it.
    EXPECT_LT(r.error.p99_relative, 0.15);
}

// The default scene's valley haze: visibility 150 m, 60 m deep under its base (at 60 m here)
// and 25 m of scale height above, g 0.6.
g::HeightFog valley_haze()
{
    g::HeightFog h;
    h.extinction = 0.02;
    h.base = 60.0;
    h.scale_height = 25.0;
    h.anisotropy = 0.6;
    return h;
}

TEST_F(FroxelGl, ADenseHazeFromAboveUnderALowSun)
{
    // A valley haze as the default scene's: 150 m visibility, 60 m deep under its base and 25 m
    // of scale height above, seen from 4 km up through slices about 600 m deep there, the sun
    // 20 degrees up. Its sunlit top is what the eye sees, its shaded depths where a froxel's one
    // light point sat: lit there, the haze came out 4.9 % too dark on average (p99 8.8 %).
    const g::Terrain ground = flat_ground();
    g::FroxelOptions o = small(24, 14);
    o.height_fog = valley_haze();
    SunLight light = sun();
    light.direction = {-0.8, 0.3, 0.31};
    Camera c;
    c.position = {0.0, -1500.0, 4000.0};
    c.target = {0.0, 0.0, 0.0};
    const Compared r = compare(ground, nullptr, o, c, 96, 54, light);
    EXPECT_GT(r.error.fog_pixels, 96 * 54 / 2);
    EXPECT_LT(r.error.mean_relative, 0.01);
    EXPECT_LT(r.error.p99_relative, 0.03);
}

TEST_F(FroxelGl, ABlanketOverAHazeFromAfar)
{
    // A 300 m blanket (optical thickness 0.9, the fitted multiple scattering) over a 150 m
    // visibility haze, seen from 10 km off and 3 km up, the sun 20 degrees up: the default
    // scene's two media. With one light per froxel for both, the haze's stood for the blanket's
    // light; with the slices over every depth a height fog may be at, the blanket's light was
    // looked up across slices a kilometre deep: 8.7 % off on average (p99 16.6 %).
    const g::Terrain ground = flat_ground(6000.0, 100.0);
    g::FroxelOptions o = small(24, 14);
    o.far = 20000.0;
    o.height_fog = valley_haze();
    const g::Medium fog = slab(150.0, 450.0, 0.003, 6000.0, 0.8, 0);
    SunLight light = sun();
    light.direction = {-0.75, 0.35, 0.32};
    Camera c;
    c.position = {-4000.0, -9000.0, 3000.0};
    c.target = {0.0, 0.0, 0.0};
    const Compared r = compare(ground, &fog, o, c, 96, 54, light);
    EXPECT_GT(r.error.fog_pixels, 96 * 54 / 2);
    EXPECT_LT(r.error.mean_relative, 0.01);
    EXPECT_LT(r.error.p99_relative, 0.06);
}

TEST_F(FroxelGl, ADenseLakesSunlitTopAtAGrazingView)
{
    // A fog lake as the bundled one (visibility 150 m, the fitted multiple scattering, the sun
    // 19 degrees up) filling parallel valleys 400 m apart to 100 m, ridges rising through it, seen
    // from 14 km off and 4.5 km up: threads of fog a pixel or two wide, whose pixels march their
    // own rays, here in 12 steps (the preview's moving frames). Across four steps the sun's share
    // of the light falls severalfold where a ray enters the fog's sunlit top; taken at every
    // fourth step and linear in between, the steps between came out too bright: 2.31 % off on
    // average. Lit at each step's ends where the four steps' ends differ by more than 40 %
    // (froxel_march.glsl): 1.17 %.
    const g::Terrain ground = parallel_valleys(8000.0);
    const g::Medium fog = slab(0.0, 100.0, 0.02, 8000.0, 0.8, 0);
    g::FroxelOptions o = small(48, 27);
    o.far = 30000.0;
    o.pixel_steps = 12;
    SunLight light = sun();
    light.direction = {-0.75, 0.35, 0.32};
    Camera c;
    c.position = {-2000.0, -14000.0, 4500.0};
    c.target = {0.0, 0.0, 0.0};
    const Compared r = compare(ground, &fog, o, c, 192, 108, light);
    EXPECT_GT(r.error.fog_pixels, 5000);
    EXPECT_LT(r.error.mean_relative, 0.016);
    EXPECT_LT(r.error.p99_relative, 0.10);
}

TEST_F(FroxelGl, ThinLayerAt30Metres)
{
    // A 2 m layer of ground fog on flat ground seen from 5 m up, judged where the ground is 25
    // to 35 m away. Standard slicing (exponential from 1 m to the far side, 1 km) puts the
    // layer inside a slice or two there; fog-aware slicing spreads the tile's slices over it.
    const g::Terrain ground = flat_ground(1200.0, 10.0);
    const g::Medium layer = slab(0.0, 2.0, 0.05, 600.0);
    Camera c;
    c.position = {0.0, -30.0, 5.0};
    c.target = {0.0, 0.0, 0.0};
    g::FroxelOptions o = small(24, 14);
    o.far = 1000.0;
    const Compared aware = compare(ground, &layer, o, c, 96, 54, sun(), 25.0, 35.0);
    EXPECT_GT(aware.error.fog_pixels, 200);
    EXPECT_LT(aware.error.mean_relative, 0.02);
    EXPECT_LT(aware.error.p99_relative, 0.05);
    o.fog_aware = false;  // and one sample per froxel, like the engines
    o.density_samples = 1;
    const Compared standard64 = compare(ground, &layer, o, c, 96, 54, sun(), 25.0, 35.0);
    o.slices = 32;
    const Compared standard32 = compare(ground, &layer, o, c, 96, 54, sun(), 25.0, 35.0);
    EXPECT_GT(standard64.error.mean_relative, 2.0 * aware.error.mean_relative);
    EXPECT_GT(standard32.error.mean_relative, standard64.error.mean_relative);
    // The whole picture (9 m to the horizon) with fog-aware slicing.
    o.fog_aware = true;
    o.slices = 64;
    o.density_samples = 2;
    const Compared whole = compare(ground, &layer, o, c, 96, 54);
    EXPECT_LT(whole.error.mean_relative, 0.02);
}

}  // namespace

namespace {

// A hill under a homogeneous fog slab, seen from outside it.
struct HillScene {
    g::Terrain ground = kiri::test::gaussian_hill(65, 20.0, 300.0, 250.0);
    g::Medium fog = slab(0.0, 150.0, 0.01, 640.0);
    static Camera camera()
    {
        Camera c;
        c.position = {-900.0, -1100.0, 500.0};
        c.target = {0.0, 0.0, 60.0};
        return c;
    }
};

TEST_F(FroxelGl, StaticViewAndFogRerunNothing)
{
    HillScene s;
    Renderer r;
    r.set_terrain(s.ground);
    r.set_sun(sun());
    g::FroxelOptions o = small(20, 12, 32);
    r.set_froxel_fog(&s.fog, o);
    for (int frame = 0; frame < 4; ++frame) {
        r.draw(HillScene::camera(), 80, 48);
        EXPECT_TRUE(r.last_stats().froxel.visible);
        EXPECT_EQ(r.last_stats().froxel.updated, frame == 0) << frame;
    }
    EXPECT_EQ(r.last_stats().froxel.updates, 1);
    EXPECT_EQ(r.last_stats().shadow_map_updates, 1);
    // A frame that reruns nothing times no pass of the volume.
    for (const auto& p : r.last_stats().passes)
        EXPECT_TRUE(p.pass != "froxel density" && p.pass != "froxel lighting") << p.pass;
    // The view moves: the volume follows; the sun's shadow map stays.
    Camera moved = HillScene::camera();
    moved.position.x += 50.0;
    r.draw(moved, 80, 48);
    EXPECT_TRUE(r.last_stats().froxel.updated);
    EXPECT_EQ(r.last_stats().shadow_map_updates, 1);
    // The fog's time moves (its noise drifts): the volume follows.
    s.fog.set_time(10.0);
    r.draw(moved, 80, 48);
    EXPECT_TRUE(r.last_stats().froxel.updated);
    EXPECT_EQ(r.last_stats().froxel.updates, 3);
    // With the temporal filter the changed fog is a moving frame (one jittered sample, the
    // history), and the same view once more a still (its samples at once); then nothing reruns.
    o.temporal = true;
    r.set_froxel_fog(&s.fog, o);
    int updates = 0;
    for (int frame = 0; frame < 6; ++frame) {
        r.draw(moved, 80, 48);
        updates += r.last_stats().froxel.updated;
        EXPECT_EQ(r.last_stats().froxel.converged, frame > 0) << frame;
    }
    EXPECT_EQ(updates, 2);
}

TEST_F(FroxelGl, FogOffScreenCostsNothing)
{
    HillScene s;
    Renderer r;
    r.set_terrain(s.ground);
    r.set_sun(sun());
    r.set_froxel_fog(&s.fog, small(20, 12, 32));
    Camera away;  // outside the fog's box, looking away from it
    away.position = {0.0, -1500.0, 400.0};
    away.target = {0.0, -3000.0, 300.0};
    for (int frame = 0; frame < 2; ++frame) {
        r.draw(away, 80, 48);
        EXPECT_FALSE(r.last_stats().froxel.visible);
        EXPECT_FALSE(r.last_stats().froxel.updated);
        EXPECT_EQ(r.last_stats().froxel.updates, 0);
        for (const auto& p : r.last_stats().passes)
            EXPECT_TRUE(p.pass.rfind("froxel", 0) != 0) << p.pass;
    }
    // Turning to it runs the passes.
    r.draw(HillScene::camera(), 80, 48);
    EXPECT_TRUE(r.last_stats().froxel.visible);
    EXPECT_EQ(r.last_stats().froxel.updates, 1);
}

// The number of fields of an aggregate: the most initialisers T{...} takes.
struct AnyField {
    template <class T>
    operator T() const;
};
template <class T, std::size_t... I>
constexpr bool takes_initialisers(std::index_sequence<I...>)
{
    return requires { T{(void(I), AnyField{})...}; };
}
template <class T, std::size_t N = 0>
constexpr std::size_t aggregate_fields()
{
    if constexpr (takes_initialisers<T>(std::make_index_sequence<N + 1>{}))
        return aggregate_fields<T, N + 1>();
    else
        return N;
}

TEST_F(FroxelGl, EveryOptionChangeReruns)
{
    // One change per field of FroxelOptions and of its height fog: the table must grow with
    // the structs, so an option the volume ignores when deciding to rerun cannot go unnoticed.
    using Change = std::pair<const char*, void (*)(g::FroxelOptions&)>;
    const Change changes[] = {
        {"width", [](g::FroxelOptions& o) { o.width = 24; }},
        {"height", [](g::FroxelOptions& o) { o.height = 14; }},
        {"slices", [](g::FroxelOptions& o) { o.slices = 24; }},
        {"distribution", [](g::FroxelOptions& o) { o.distribution = g::SliceDistribution::log2; }},
        {"power", [](g::FroxelOptions& o) { o.power = 3.0; }},
        {"log2_scale", [](g::FroxelOptions& o) { o.log2_scale = 16.0; }},
        {"near", [](g::FroxelOptions& o) { o.near = 2.0; }},
        {"far", [](g::FroxelOptions& o) { o.far = 5000.0; }},
        {"fog_aware", [](g::FroxelOptions& o) { o.fog_aware = !o.fog_aware; }},
        {"temporal", [](g::FroxelOptions& o) { o.temporal = !o.temporal; }},
        {"history_weight", [](g::FroxelOptions& o) { o.history_weight = 0.5; }},
        {"density_samples", [](g::FroxelOptions& o) { o.density_samples = 3; }},
        {"sun_steps", [](g::FroxelOptions& o) { o.sun_steps = 8; }},
        {"sun_volume", [](g::FroxelOptions& o) { o.sun_volume = !o.sun_volume; }},
        {"pixel_steps", [](g::FroxelOptions& o) { o.pixel_steps = 16; }},
        {"upsample", [](g::FroxelOptions& o) { o.upsample = 0.05; }},
        {"terrain_shadows", [](g::FroxelOptions& o) { o.terrain_shadows = !o.terrain_shadows; }},
        {"fog_shadows", [](g::FroxelOptions& o) { o.fog_shadows = !o.fog_shadows; }},
        {"shadow_map_size", [](g::FroxelOptions& o) { o.shadow_map_size = 512; }},
        {"esm_sharpness", [](g::FroxelOptions& o) { o.esm_sharpness = 2.0; }},
        {"height_fog.extinction", [](g::FroxelOptions& o) { o.height_fog.extinction = 0.001; }},
        {"height_fog.base", [](g::FroxelOptions& o) { o.height_fog.base = 50.0; }},
        {"height_fog.scale_height", [](g::FroxelOptions& o) { o.height_fog.scale_height = 60.0; }},
        {"height_fog.albedo", [](g::FroxelOptions& o) { o.height_fog.albedo = 0.5; }},
        {"height_fog.anisotropy", [](g::FroxelOptions& o) { o.height_fog.anisotropy = 0.2; }},
        {"height_fog.min",
         [](g::FroxelOptions& o) {
             o.height_fog.min = {-2000.0, -2000.0};
         }},
        {"height_fog.max",
         [](g::FroxelOptions& o) {
             o.height_fog.max = {2000.0, 2000.0};
         }},
    };
    ASSERT_EQ(std::size(changes), aggregate_fields<g::FroxelOptions>() - 1 + aggregate_fields<g::HeightFog>());
    HillScene s;
    Renderer r;
    r.set_terrain(s.ground);
    r.set_sun(sun());
    const g::FroxelOptions base = small(20, 12, 32);
    for (const auto& [field, change] : changes) {
        g::FroxelOptions changed = base;
        change(changed);
        ASSERT_FALSE(changed == base) << field;
        r.set_froxel_fog(&s.fog, base);
        r.draw(HillScene::camera(), 80, 48);
        r.draw(HillScene::camera(), 80, 48);
        ASSERT_FALSE(r.last_stats().froxel.updated) << field << ": the unchanged options rerun";
        r.set_froxel_fog(&s.fog, changed);
        r.draw(HillScene::camera(), 80, 48);
        EXPECT_TRUE(r.last_stats().froxel.updated) << field;
    }
}

TEST_F(FroxelGl, TemporalFilterConvergesAndDoesNotGhost)
{
    HillScene s;
    g::FroxelOptions o = small(24, 14);
    const Camera c = HillScene::camera();
    const double still = compare(s.ground, &s.fog, o, c, 96, 56).error.mean_relative;
    // A still (the first view) takes its jittered samples at once: final in one frame, and as
    // close to the reference as the unjittered one.
    o.temporal = true;
    Renderer r;
    r.set_terrain(s.ground);
    r.set_sun(sun());
    r.set_froxel_fog(&s.fog, o);
    r.draw(c, 96, 56);
    EXPECT_TRUE(r.last_stats().froxel.converged);
    for (int frame = 0; frame < 3; ++frame) {
        r.draw(c, 96, 56);
        EXPECT_FALSE(r.last_stats().froxel.updated);
    }
    g::ReferenceView view;
    view.eye = c.position;
    view.target = c.target;
    view.width = 96;
    view.height = 56;
    view.max_depth = o.far;
    const g::ReferenceImage before =
        g::render_reference_fog({&s.fog, {}}, &s.ground.heightfield(), view, lighting(sun(), o, &s.fog, s.ground));
    r.render(c, 96, 56);
    const double converged = kiri::render::compare_fog(r.read_froxel_fog(), before).mean_relative;
    EXPECT_LT(converged, std::max(1.5 * still, 0.02));  // the jittered average blurs J over the tile
    // The sun jumps to the other side: one frame later the old light is gone (the history is
    // clamped to what the current samples allow), not blended in at 90 %.
    SunLight other = sun();
    other.direction = {0.7, -0.4, 0.5};
    r.set_sun(other);
    r.draw(c, 96, 56);
    EXPECT_FALSE(r.last_stats().froxel.converged);
    const FogBuffer after = r.read_froxel_fog();
    expect_finite(after);
    const g::ReferenceImage truth =
        g::render_reference_fog({&s.fog, {}}, &s.ground.heightfield(), view, lighting(other, o, &s.fog, s.ground));
    const double stale = kiri::render::compare_fog(r.read_froxel_fog(), before).mean_relative;
    const double fresh = kiri::render::compare_fog(after, truth).mean_relative;
    std::printf("    still %.4f, converged %.4f, after the sun moved %.4f (against the old sun %.4f)\n", still,
                converged, fresh, stale);
    // As close as a frame without history gets: the same still first, then the light jumps to
    // `light` as the view reaches cam (one jittered sample, no history).
    const auto without_history = [&](const SunLight& light, const Camera& cam, const g::ReferenceImage& ref) {
        Renderer q;
        q.set_terrain(s.ground);
        q.set_sun(sun());
        q.set_froxel_fog(&s.fog, o);
        q.draw(c, 96, 56);
        q.set_sun(light);
        q.draw(cam, 96, 56);
        return kiri::render::compare_fog(q.read_froxel_fog(), ref).mean_relative;
    };
    const double baseline = without_history(other, c, truth);
    std::printf("    a frame without history under the new sun %.4f\n", baseline);
    EXPECT_LT(fresh, std::max(1.5 * baseline, 0.01));
    EXPECT_LT(fresh, 0.5 * stale);
    // The camera moves by a tile or so: reprojection keeps the picture right.
    Camera moved = c;
    moved.position += glm::dvec3(40.0, -30.0, 10.0);
    r.draw(moved, 96, 56);
    view.eye = moved.position;
    const g::ReferenceImage truth_moved =
        g::render_reference_fog({&s.fog, {}}, &s.ground.heightfield(), view, lighting(other, o, &s.fog, s.ground));
    const double moved_error = kiri::render::compare_fog(r.read_froxel_fog(), truth_moved).mean_relative;
    EXPECT_LT(moved_error, std::max(1.5 * without_history(other, moved, truth_moved), 0.01));
}

TEST_F(FroxelGl, AnisotropyNearOneAgreesWithTheReference)
{
    // g near the edge of (-1, 1) yet inside the clamp (|g| < 0.999), its lobe in view: the sun low
    // ahead for the forward lobe (g > 0), low behind for the backward one (g < 0).
    // Measured mean errors: 0.017 (g 0.998), 0.031 (-0.998), 0.059 (0.99), 0.057 (-0.99).
    const g::Terrain ground = flat_ground();
    for (const auto& [g_aniso, bound] : {std::pair{0.998, 0.02}, {-0.998, 0.037}, {0.99, 0.07}, {-0.99, 0.07}}) {
        const g::Medium fog = slab(0.0, 400.0, 0.004, 2000.0, g_aniso);
        SunLight light = sun();
        light.direction = {0.0, g_aniso > 0.0 ? 1.0 : -1.0, 0.12};
        Camera c;
        c.position = {0.0, -1500.0, 150.0};
        c.target = {0.0, 0.0, 250.0};
        g::FroxelOptions o = small(16, 9);
        o.far = 3000.0;
        const Compared r = compare(ground, &fog, o, c, 64, 36, light);
        std::printf("    g %+.3f: mean error %.4f, p99 %.3f\n", g_aniso, r.error.mean_relative, r.error.p99_relative);
        EXPECT_LT(r.error.mean_relative, bound) << g_aniso;
    }
}

TEST_F(FroxelGl, AnisotropyIsClampedToWithinOneThousandthOfOne)
{
    // Henyey-Greenstein's lobe grows without bound as |g| -> 1, so every phase in kiri clamps g to
    // [-0.999, 0.999] (docs/medium.md, fog_lighting.glsl): g = +-0.9999999 draws the fog of
    // g = +-0.999 on the GPU and in the reference, and the clamp is no wider than that (g = 0.998
    // draws another fog).
    const g::Terrain ground = flat_ground();
    Camera c;
    c.position = {0.0, -1500.0, 150.0};
    c.target = {0.0, 0.0, 250.0};
    g::FroxelOptions o = small(16, 9);
    o.far = 3000.0;
    auto draw = [&](double g_aniso) {
        const g::Medium fog = slab(0.0, 400.0, 0.004, 2000.0, g_aniso);
        SunLight light = sun();
        light.direction = {0.0, g_aniso > 0.0 ? 1.0 : -1.0, 0.12};  // the lobe in view, as above
        return compare(ground, &fog, o, c, 64, 36, light);
    };
    auto largest_difference = [](const std::vector<float>& a, const std::vector<float>& b) {
        double d = 0.0;
        for (std::size_t k = 0; k < a.size(); ++k)
            d = std::max(d, double(std::abs(a[k] - b[k])) / std::max(double(std::abs(b[k])), 1e-6));
        return d;
    };
    for (double sign : {1.0, -1.0}) {
        const Compared edge = draw(sign * 0.9999999), clamped = draw(sign * 0.999), inside = draw(sign * 0.998);
        EXPECT_LT(edge.error.mean_relative, sign > 0.0 ? 0.013 : 0.027) << sign;  // measured 0.0105, 0.0225
        std::vector<float> ref_edge, ref_clamped, ref_inside;
        for (const auto* r : {&edge, &clamped, &inside}) {
            std::vector<float>& out = r == &edge ? ref_edge : r == &clamped ? ref_clamped : ref_inside;
            for (const glm::dvec3& v : r->reference.inscatter)
                out.insert(out.end(), {float(v.x), float(v.y), float(v.z)});
        }
        const double gpu_same = largest_difference(edge.gpu.rgba, clamped.gpu.rgba);
        const double ref_same = largest_difference(ref_edge, ref_clamped);
        const double gpu_other = largest_difference(inside.gpu.rgba, clamped.gpu.rgba);
        const double ref_other = largest_difference(ref_inside, ref_clamped);
        std::printf("    g %+.7f against %+.3f: GPU %.2e, reference %.2e; g %+.3f: GPU %.3f, reference %.3f\n",
                    sign * 0.9999999, sign * 0.999, gpu_same, ref_same, sign * 0.998, gpu_other, ref_other);
        EXPECT_EQ(gpu_same, 0.0) << sign;
        EXPECT_EQ(ref_same, 0.0) << sign;
        EXPECT_GT(gpu_other, 0.01) << sign;
        EXPECT_GT(ref_other, 0.01) << sign;
    }
    // g = 1 itself is refused, not rendered.
    g::FroxelOptions one = small(24, 14);
    one.height_fog.extinction = 0.001;
    one.height_fog.anisotropy = 1.0;
    Renderer r;
    EXPECT_THROW(r.set_froxel_fog(nullptr, one), kiri::InputError);
}

}  // namespace

TEST_F(FroxelGl, CombinedFroxelsLeaveTheParticlesOnlyFogThickForThem)
{
    // Combined mode with the particles' band the whole shell (share 1, band 1): the froxels draw
    // 1 - s(h) w(t) of a 300 m slab, w the particles' share by the fog's thickness t
    // (particle_depth 8 radii: none below 8 r / 3, all from 8 r). The particles' radius sets
    // where: r = 200 m leaves them nothing (the froxels draw the whole slab), r = 37.5 m all of
    // their band (the froxels draw int (1 - s) = half of it, s the quintic step, symmetric), and
    // r = 56.25 m half of it (300 m is midway through the step), so the optical depth the froxels
    // draw is the mean of the two. Read from each pixel's transmittance, looking down.
    const g::Terrain ground = flat_ground();
    const g::Medium fog = slab(0.0, 300.0, 0.003);
    Camera c;
    c.position = {0.0, -400.0, 1500.0};
    c.target = {0.0, 0.0, 0.0};
    c.fov_y_deg = 30.0;
    const g::FroxelOptions o = small(24, 14);
    Renderer r;
    r.set_terrain(ground);
    r.set_sun(sun());
    r.set_froxel_fog(&fog, o);
    const auto optical_depths = [&](std::optional<double> radius) {
        std::optional<g::FogPartition> p;
        if (radius) {
            p.emplace();
            p->particle_share = 1.0;
            p->particle_band = 1.0;
            p->particle_depth = 8.0;
            p->particle_radius = *radius;
        }
        r.set_fog_partition(p);
        r.render(c, 48, 27);
        const kiri::render::FogBuffer f = r.read_froxel_fog();
        std::vector<double> tau;
        for (std::size_t k = 0; k + 3 < f.rgba.size(); k += 4)
            tau.push_back(-std::log(std::max(double(f.rgba[k + 3]), 1e-30)));
        return tau;
    };
    const std::vector<double> whole = optical_depths(std::nullopt), none = optical_depths(200.0),
                              all = optical_depths(37.5), half = optical_depths(56.25);
    ASSERT_EQ(whole.size(), std::size_t(48 * 27));
    double mean_whole = 0.0, mean_all = 0.0, off_none = 0.0, off_half = 0.0;
    for (std::size_t k = 0; k < whole.size(); ++k) {
        mean_whole += whole[k] / double(whole.size());
        mean_all += all[k] / double(whole.size());
        off_none = std::max(off_none, std::abs(none[k] - whole[k]));
        off_half = std::max(off_half, std::abs(half[k] - 0.5 * (none[k] + all[k])));
    }
    EXPECT_GT(mean_whole, 0.5);  // the slab's 0.9 over the view's slant
    EXPECT_NEAR(mean_all / mean_whole, 0.5, 0.03);
    EXPECT_LT(off_none, 1e-5);
    EXPECT_LT(off_half, 1e-3 * mean_whole);
}
