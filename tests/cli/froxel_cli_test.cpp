// `kiri render --mode froxel|reference` and `kiri author`'s medium.vdb as a user runs them.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "cli/kiri_runner.hpp"
#include "kiri/render/image.hpp"

namespace fs = std::filesystem;
using kiri::test::run_kiri;

namespace {

const std::string lake = (fs::path(KIRI_DATA_DIR) / "scenes/jacksboro_lake.json").string();

double mean_abs_difference(const kiri::render::Image& a, const kiri::render::Image& b)
{
    double sum = 0.0;
    for (std::size_t i = 0; i < a.rgba.size(); ++i)
        sum += std::abs(int(a.rgba[i]) - int(b.rgba[i]));
    return sum / double(a.rgba.size());
}

}  // namespace

TEST(KiriFroxel, RendersTheFogAsAVolumeAndTheReferenceAgrees)
{
    const fs::path bare = kiri::test::temp_path("froxel_cli_bare.png"),
                   fog = kiri::test::temp_path("froxel_cli_fog.png"), ref = kiri::test::temp_path("froxel_cli_ref.png");
    const std::string size = " --width 64 --height 36 --camera sun";
    ASSERT_EQ(run_kiri("render " + lake + " -o " + bare.string() + size + " --mode terrain").exit_code, 0);
    const auto r = run_kiri("render " + lake + " -o " + fog.string() + size + " --mode froxel");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, fog.string() + "\n");
    const auto q = run_kiri("render " + lake + " -o " + ref.string() + size + " --mode reference");
    ASSERT_EQ(q.exit_code, 0) << q.err;
    const auto a = kiri::render::read_png(bare), b = kiri::render::read_png(fog), c = kiri::render::read_png(ref);
    ASSERT_EQ(b.width, 64);
    ASSERT_EQ(c.height, 36);
    // The fog changes the picture a lot; the reference (its own terrain shading, no haze) and
    // the froxel frame are far closer to each other than to the picture without fog.
    EXPECT_GT(mean_abs_difference(a, b), 8.0);
    EXPECT_LT(mean_abs_difference(b, c), 0.5 * mean_abs_difference(a, c));
    for (const auto& p : {bare, fog, ref})
        fs::remove(p);
}

TEST(KiriFroxel, NoFogToRenderIsOneLineAndExit2)
{
    const fs::path scene = kiri::test::temp_path("froxel_cli_nofog.json");
    std::ofstream(scene) << R"({"terrain": {"path": ")"
                         << (fs::path(KIRI_DATA_DIR) / "terrains/jacksboro_fault_dem.tif").string() << R"("}})";
    const fs::path out = kiri::test::temp_path("froxel_cli_nofog.png");
    const auto r = run_kiri("render " + scene.string() + " -o " + out.string() + " --mode froxel");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err, "kiri: " + scene.string() + ": /fog: mode froxel needs a fog section or a froxel height fog\n");
    EXPECT_FALSE(fs::exists(out));
    fs::remove(scene);
}

TEST(KiriFroxel, AuthorWritesTheMediumAsOpenVdb)
{
    const fs::path dir = kiri::test::temp_path("froxel_cli_author");
    fs::remove_all(dir);
    const auto r = run_kiri("author " + lake + " -o " + dir.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string vdb = kiri::test::read_all(dir / "medium.vdb");
    // OpenVDB's magic number (0x56444220, " BDV" little-endian) opens the file.
    ASSERT_GT(vdb.size(), 1000u);
    EXPECT_EQ(vdb.substr(0, 4), std::string(" BDV"));
    EXPECT_NE(r.out.find("voxels of"), std::string::npos);
    fs::remove_all(dir);
}
