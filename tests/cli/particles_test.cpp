// Particle fog as users meet it: `kiri render --mode particles` and `kiri author`'s particles.ply,
// and a bad "particles" key refused in one line.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/kiri_runner.hpp"
#include "cli/reference_judge.hpp"
#include "cli/shipped_scene.hpp"
#include "kiri/render/image.hpp"

namespace fs = std::filesystem;
using kiri::test::run_kiri;

namespace {

const std::string default_scene = (fs::path(KIRI_DATA_DIR) / "scenes/jacksboro.json").string();

// `kiri render --mode particles` of a scene's camera at width x height against the CPU reference,
// each over the bare terrain's frame; printed with `what`.
kiri::render::FogError particles_against_reference(const std::string& scene, const std::string& camera, int width,
                                                   int height, const char* what)
{
    const std::string args =
        "--width " + std::to_string(width) + " --height " + std::to_string(height) + " --camera " + camera;
    const kiri::render::RadianceImage fog = kiri::test::render_radiance(scene, "particles", args);
    const kiri::render::RadianceImage bare = kiri::test::render_radiance(scene, "terrain", args);
    const kiri::geometry::ReferenceImage reference = kiri::test::scene_reference(scene, camera, width, height, false);
    const kiri::render::FogError e = kiri::render::compare_frames(fog, bare, reference);
    std::printf("    %s: %d fog pixels, mean error %.4f, p99 %.3f\n", what, e.fog_pixels, e.mean_relative,
                e.p99_relative);
    return e;
}

}  // namespace

TEST(KiriParticles, RenderDrawsLitParticleFog)
{
    // The default scene's first camera at 64 x 36: the particles' frame against the CPU
    // reference of the same fog (reference_judge.hpp), as `kiri bench --stage agreement` judges it.
    const fs::path out = kiri::test::temp_path("particles_fog.exr");
    const auto r =
        run_kiri("render " + default_scene + " -o " + out.string() + " --width 64 --height 36 --mode particles");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("20000 particles of 100000 candidates ("), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("attenuation buffer 128x128x128 R16F (4.0 MiB)"), std::string::npos) << r.err;
    const kiri::render::RadianceImage fog = kiri::render::read_exr(out);
    fs::remove(out);
    const kiri::render::RadianceImage bare =
        kiri::test::render_radiance(default_scene, "terrain", "--width 64 --height 36");
    const kiri::geometry::ReferenceImage reference = kiri::test::scene_reference(default_scene, "", 64, 36, false);
    // Measured 0.081 (in the terrain's shadows; this view's sun casts few into the fog).
    const double bound = 0.095;
    // A grey overlay in place of the fog does not pass: a uniform veil over the bare frame, as
    // bright on average as the fog (measured at least 0.138).
    kiri::test::expect_fog_agrees("particles", fog, bare, reference, 64 * 36 / 3, bound);
}

TEST(KiriParticles, FromUnderTheBlanketLevelRaysCrossNoBallsBelowItsFloor)
{
    // The default scene from the frame bench's valley view: the eye in the clear air under the
    // blanket's floating bottom, level rays under it to the far valley walls. A ball was cut at a
    // level plane under the lowest floor over its disc, so slivers of thousands of balls hung
    // under the sloping bottom across those rays.
    nlohmann::json scene = kiri::test::shipped_scene("jacksboro");
    scene["cameras"].push_back(
        {{"name", "valley"}, {"position", {8197, -9020, 544}}, {"target", {7049, -6248, 484}}, {"fov", 60}});
    const fs::path file = kiri::test::write_temp_scene(scene, "particles_valley.json");
    const kiri::render::FogError e =
        particles_against_reference(file.string(), "valley", 160, 90, "from under the blanket");
    fs::remove(file);
    EXPECT_GT(e.fog_pixels, 160 * 90 / 3);
    // Measured 0.146 (p99 1.19; 0.174 and 1.38 before the near field); cut at the level plane
    // under the lowest floor, 0.453 (p99 7.06).
    EXPECT_LT(e.mean_relative, 0.25);
}

TEST(KiriParticles, FromAShoreLevelRaysSeeNoBallsOverTheLakesTop)
{
    // The fill's valley view: the eye over a fog lake's flat top, looking across it to its far
    // shore. Balls near the top stood out of it, and rays passing over the top to the far shore
    // crossed their upper parts: a bright veil over the shore, the frame's worst pixels.
    const std::string fill = (fs::path(KIRI_DATA_DIR) / "scenes/jacksboro_fill.json").string();
    const kiri::render::FogError e = particles_against_reference(fill, "valley", 96, 54, "from the fill's shore");
    EXPECT_GT(e.fog_pixels, 96 * 54 / 4);
    // Measured p99 0.53 (mean 0.053; the near field is not drawn: the eye is farther from the
    // fog); without the cut at the top's plane, 1.37 (measured 2026-12-06). Drawn at each sample
    // in the Medium's light (2026-12-07, night): p99 0.76, mean 0.050; with the widened
    // billboards lit at their balls' centres too, p99 0.88, and not spread over the pixels whose
    // own ray meets no fog (the lake's far edge widened into a veil over the shore behind it,
    // docs/particles.md, "Widened billboards lit where their balls are"): p99 0.647, mean 0.047.
    EXPECT_LT(e.p99_relative, 0.72);
}

TEST(KiriParticles, FromInsideTheFogTheNearFieldIsTheMediumItself)
{
    // The descent's camera inside the blanket: within 2.5 radii of the eye the particles' renderer
    // marches the Medium itself, the billboards the fog beyond. A few balls 160 m in radius stood
    // for all the fog near the eye, each a blot over a large part of the frame: along the rays of
    // the frame's lowest rows, towards the ground, they held 20 % more optical depth than the
    // Medium (docs/particles.md, "The near field").
    const std::string descent = (fs::path(KIRI_DATA_DIR) / "scenes/jacksboro_descent.json").string();
    const kiri::render::FogError e =
        particles_against_reference(descent, "descent_3_inside", 96, 54, "inside the descent's blanket");
    EXPECT_GT(e.fog_pixels, 96 * 54 / 2);
    // Measured 0.021 (p99 0.18); with "particles": {"near_field": 0} (the billboards up to the
    // eye) 0.051 (p99 0.25).
    EXPECT_LT(e.mean_relative, 0.035);
}

TEST(KiriParticles, AuthorWritesParticlesPly)
{
    const fs::path dir = kiri::test::temp_path("particles_author");
    fs::remove_all(dir);
    const auto r = run_kiri("author " + default_scene + " -o " + dir.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("20000 particles"), std::string::npos) << r.out;
    const std::string ply = kiri::test::read_all(dir / "particles.ply");
    EXPECT_EQ(ply.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
    EXPECT_NE(ply.find("element vertex 20000\n"), std::string::npos);
    const std::size_t end = ply.find("end_header\n");
    ASSERT_NE(end, std::string::npos);
    EXPECT_EQ(ply.size(), end + 11 + 20000u * 13u * 4u);
    // The pipeline's cloud: each particle's share above the ground and its floor and top, as drawn.
    EXPECT_NE(ply.find("property float above_ground\nproperty float floor\n"), std::string::npos);
    EXPECT_NE(ply.find("property float top\nproperty float top_dzdx\nproperty float top_dzdy\n"), std::string::npos);
    fs::remove_all(dir);
}

TEST(KiriParticles, BadKeyIsOneLine)
{
    const fs::path scene = kiri::test::temp_path("particles_bad.json"),
                   out = kiri::test::temp_path("particles_bad.png");
    {
        std::ofstream s(scene);
        s << R"({"terrain": {"path": ")" << (fs::path(KIRI_DATA_DIR) / "terrains/jacksboro_fault_dem.tif").string()
          << R"("}, "fog": {}, "particles": {"count": 100, "resolution": 1000}})";
    }
    const auto r = run_kiri("render " + scene.string() + " -o " + out.string() + " --mode particles");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.error_lines(), 1) << r.err;
    EXPECT_EQ(r.err, "kiri: " + scene.string() + ": /particles/resolution: must be in [16, 512], got 1000\n");
    EXPECT_FALSE(fs::exists(out));
    fs::remove(scene);
}
