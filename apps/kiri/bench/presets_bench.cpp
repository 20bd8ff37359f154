// The quality presets (geometry/quality.hpp) of the default scene as users render it: combined
// mode, its first camera, its height fog included (the reference judges the Medium and the
// height fog). Cost per frame at 1280x720 and 640x360; the error at a size the CPU reference can
// afford (320x180; --quick: 160x90).
#include <cstdio>
#include <fstream>
#include <string>

#include "bench/bench.hpp"
#include "bench/fog_judge.hpp"
#include "kiri/geometry/scene/quality.hpp"

namespace kiri::bench {
namespace {

void presets(Context& c)
{
    SceneJson source(c.data_dir() / "scenes/jacksboro.json");
    const geometry::Scene scene = source.parse(source.root);
    const int w = c.quick() ? 160 : 320, h = c.quick() ? 90 : 180;
    FogJudge judge(scene, "", w, h);
    std::printf("  reference %dx%d (first camera): %.1f s\n", w, h, judge.reference_seconds());
    std::vector<std::pair<int, int>> sizes = {{640, 360}};
    if (!c.quick())
        sizes.push_back({1280, 720});
    const int frames = c.quick() ? 2 : 3;

    std::ofstream md(c.out_dir() / "presets.md");
    md << "| preset | layers | particles (buffer) | froxels | particle share |";
    for (const auto& [sw, sh] : sizes)
        md << " frame " << sw << "x" << sh << " (ms) |";
    md << " mean error (" << w << "x" << h << ") | p99 error |\n|---|---|---|---|---|";
    for (std::size_t k = 0; k < sizes.size(); ++k)
        md << "---|";
    md << "---|---|\n";
    for (geometry::Quality q :
         {geometry::Quality::low, geometry::Quality::medium, geometry::Quality::high, geometry::Quality::ultra}) {
        nlohmann::json varied = source.root;
        varied["quality"] = geometry::to_string(q);
        judge.prepare(source.parse(varied), render::FogMode::combined);
        const render::FogError e = judge.error();
        const geometry::QualityPreset p = geometry::quality_preset(q);
        md << "| " << geometry::to_string(q) << " | " << p.layers << " at " << p.layer_resolution << " | "
           << p.particles << " (" << p.attenuation_resolution << "^3) | " << p.froxel_width << "x" << p.froxel_height
           << "x" << p.froxel_slices << " | " << p.particle_share << " |";
        for (const auto& [sw, sh] : sizes) {
            const double ms = judge.frame_ms(sw, sh, frames);
            md << ' ' << ms << " |";
            c.add({"combined " + std::to_string(sw) + "x" + std::to_string(sh), geometry::to_string(q), ms, ms / 1e3,
                   "mean relative luminance error at " + std::to_string(w) + "x" + std::to_string(h), e.mean_relative,
                   0.0, 0.0});
            std::printf("  %-6s %dx%d %9.1f ms  mean %6.2f %%  p99 %6.2f %%\n", geometry::to_string(q), sw, sh, ms,
                        e.mean_relative * 100, e.p99_relative * 100);
            std::fflush(stdout);
        }
        md << ' ' << e.mean_relative * 100 << " % | " << e.p99_relative * 100 << " % |\n";
    }
}

}  // namespace

KIRI_BENCH_STAGE({"presets",
                  "Quality presets of the default scene (combined): error against the CPU reference vs frame cost",
                  {"frame (ms)", "error_value", "mean relative luminance error", true, true, true},
                  presets});

}  // namespace kiri::bench
