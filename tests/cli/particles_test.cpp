// Particle fog as users meet it: `kiri render --mode particles` and `kiri author`'s particles.ply,
// and a bad "particles" key refused in one line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli/kiri_runner.hpp"
#include "kiri/render/image.hpp"

namespace fs = std::filesystem;
using kiri::test::run_kiri;

namespace {

const std::string default_scene = (fs::path(KIRI_DATA_DIR) / "scenes/jacksboro.json").string();

double mean_difference(const kiri::render::Image& a, const kiri::render::Image& b)
{
    double sum = 0.0;
    for (std::size_t i = 0; i < a.rgba.size(); ++i)
        sum += std::abs(int(a.rgba[i]) - int(b.rgba[i]));
    return sum / double(a.rgba.size());
}

}  // namespace

TEST(KiriParticles, RenderDrawsLitParticleFog)
{
    const fs::path fog = kiri::test::temp_path("particles_fog.png"), bare = kiri::test::temp_path("particles_bare.png");
    const auto r =
        run_kiri("render " + default_scene + " -o " + fog.string() + " --width 160 --height 90 --mode particles");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("20000 particles, attenuation buffer 128x128x128 R16F (4.0 MiB)"), std::string::npos) << r.err;
    ASSERT_EQ(run_kiri("render " + default_scene + " -o " + bare.string() + " --width 160 --height 90 --mode terrain")
                  .exit_code,
              0);
    const kiri::render::Image a = kiri::render::read_png(fog), b = kiri::render::read_png(bare);
    // The fog covers most of the terrain: 7.9 levels mean under the fitted multiple scattering.
    EXPECT_GT(mean_difference(a, b), 6.0);
    fs::remove(fog);
    fs::remove(bare);
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
    EXPECT_EQ(ply.size(), end + 11 + 20000u * 6u * 4u);
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
