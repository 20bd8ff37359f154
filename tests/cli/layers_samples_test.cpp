// The layers of a still drawn at the frame's resolution take each sample's own ray (layers.frag's
// LAYERS_AT_SAMPLES), judged as the benches judge: the reference through each of the frame's
// samples where the fog bends within a pixel (apps/kiri/bench/fog_judge.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "bench/fog_judge.hpp"
#include "cli/synthetic_dem.hpp"
#include "temp_path.hpp"
#include "kiri/render/fog_error.hpp"

namespace fs = std::filesystem;

TEST(LayersAtSamples, ADenseFogsShoreIsFoggedSampleBySample)
{
    // A fog lake of 10 m visibility in a bowl seen from afar (96 x 54): a metre of it under the
    // top is a third opaque, and its shore line crosses a pixel between its samples. Drawn at
    // each pixel's centre, the layers took the centre's fog for the whole pixel, and where the
    // centre's ray met the shore above the top, none: 0.0195 against the judge (p99 0.164). Each
    // sample on its own ray, to its own ground, lit where it is: 0.0114 (p99 0.070).
    const fs::path dir = kiri::test::temp_path("layers_samples_test");
    fs::create_directories(dir);
    kiri::test::write_dem(dir / "bowl.asc", 201, [](double x, double y) {
        const double u = x / 2000.0 - 1.0, v = y / 2000.0 - 1.0;
        return 300.0 * (u * u + v * v) + 10.0 * std::sin(x / 310.0) * std::cos(y / 270.0);
    });
    {
        std::ofstream scene(dir / "dense.json");
        scene << R"({"terrain": {"path": "bowl.asc"},
  "cameras": [{"name": "far", "position": [-2300, -2300, 1100], "target": [0, 0, 100], "fov": 40}],
  "sun": {"direction": [-0.75, 0.35, 0.32], "intensity": 3.2, "ambient": [0.22, 0.28, 0.38]},
  "fog": {"footprint": {"type": "terrain", "margin": 0}, "patch_size": 1000, "mode": "lake", "altitude": 150,
          "thickness": 150},
  "layers": {"count": 15},
  "medium": {"visibility": 10, "top_density": 0.5}})";
    }
    const kiri::bench::SceneJson source(dir / "dense.json");
    kiri::bench::FogJudge judge(source.parse(source.root), "far", 96, 54);
    judge.prepare(source.parse(source.root), kiri::render::FogMode::layers);
    const kiri::render::FogError e = judge.error();
    std::printf("    the layers against the judge: %d fog pixels, mean error %.4f, p99 %.3f\n", e.fog_pixels,
                e.mean_relative, e.p99_relative);
    EXPECT_GT(e.fog_pixels, 900);
    EXPECT_LT(e.mean_relative, 0.015);
    fs::remove_all(dir);
}
