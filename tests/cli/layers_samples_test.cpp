// The layers of a still drawn at the frame's resolution take each sample's own ray (layers.frag's
// LAYERS_AT_SAMPLES), judged as the benches judge: the reference through each of the frame's
// samples where the fog bends within a pixel (apps/kiri/bench/fog_judge.hpp).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

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
    // sample on its own ray, to its own ground, lit where it is: 0.0104 (p99 0.060).
    const fs::path dir = kiri::test::temp_path("layers_samples_test");
    fs::create_directories(dir);
    const kiri::bench::SceneJson source(kiri::test::write_dense_bowl_lake(dir));
    kiri::bench::FogJudge judge(source.parse(source.root), "far", 96, 54);
    judge.prepare(source.parse(source.root), kiri::render::FogMode::layers);
    const kiri::render::FogError e = judge.error();
    std::printf("    the layers against the judge: %d fog pixels, mean error %.4f, p99 %.3f\n", e.fog_pixels,
                e.mean_relative, e.p99_relative);
    EXPECT_GT(e.fog_pixels, 900);
    EXPECT_LT(e.mean_relative, 0.015);
    fs::remove_all(dir);
}
