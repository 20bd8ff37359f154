// Agreement: layers, particles, froxels and combined drawing the same Medium of the
// default scene at increasing quality, each frame's error against the CPU reference ray marcher
// against its cost, on one log-log plot. The Medium alone is judged: the scene's froxel height
// fog, which only the froxels draw, is left out of every renderer and of the reference.
#include <array>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "bench/bench.hpp"
#include "bench/fog_judge.hpp"
#include "bench/froxel_scene.hpp"
#include "kiri/render/image.hpp"
#include "kiri/render/tone_map.hpp"

namespace kiri::bench {
namespace {

using nlohmann::json;

struct Rung {
    render::FogMode mode;
    std::string label;  //!< the point's label on the plot
    json keys;          //!< scene sections merged over the base
};

std::vector<Rung> ladder(bool quick)
{
    std::vector<Rung> r;
    const std::vector<std::pair<int, double>> layers = {{5, 0.25}, {10, 0.5}, {15, 0.5}, {30, 1.0}, {60, 1.0}};
    const std::vector<std::pair<int, int>> particles = {
        {5000, 64}, {10000, 96}, {20000, 128}, {40000, 160}, {60000, 192}};
    const std::vector<std::array<int, 3>> froxels = {
        {80, 45, 32}, {120, 68, 48}, {160, 90, 64}, {240, 135, 96}, {320, 180, 128}};
    const auto keep = [quick](std::size_t k) { return !quick || k % 2 == 0; };
    for (std::size_t k = 0; k < layers.size(); ++k)
        if (keep(k))
            r.push_back({render::FogMode::layers,
                         std::to_string(layers[k].first) + " x" + std::to_string(layers[k].second).substr(0, 4),
                         {{"layers", {{"count", layers[k].first}, {"resolution", layers[k].second}}}}});
    for (std::size_t k = 0; k < particles.size(); ++k)
        if (keep(k))
            r.push_back({render::FogMode::particles,
                         std::to_string(particles[k].first / 1000) + "k/" + std::to_string(particles[k].second),
                         {{"particles", {{"count", particles[k].first}, {"resolution", particles[k].second}}}}});
    for (std::size_t k = 0; k < froxels.size(); ++k)
        if (keep(k)) {
            const auto& f = froxels[k];
            r.push_back({render::FogMode::froxel,
                         std::to_string(f[0]) + "x" + std::to_string(f[1]) + "x" + std::to_string(f[2]),
                         {{"froxel", {{"size", {f[0], f[1], f[2]}}}}}});
        }
    for (const char* q : {"low", "medium", "high", "ultra"})
        if (!quick || std::string(q) == "low" || std::string(q) == "high")
            r.push_back({render::FogMode::combined, q, {{"quality", q}}});
    return r;
}

void agreement(Context& c)
{
    SceneJson source(c.data_dir() / "scenes/jacksboro.json");
    json base = source.root;
    base["froxel"].erase("height_fog");  // the Medium alone: only the froxels would draw the haze
    const geometry::Scene scene = source.parse(base);
    const int w = c.quick() ? 160 : 320, h = c.quick() ? 90 : 180;
    const std::string camera = "ridge";  // low over the valleys: fog from the foreground to the horizon
    FogJudge judge(scene, camera, w, h);
    std::printf("  reference %dx%d (camera %s): %.1f s\n", w, h, camera.c_str(), judge.reference_seconds());
    render::write_png_atomic(c.out_dir() / "agreement_reference.png", render::tone_mapped(judge.reference()));

    std::ofstream md(c.out_dir() / "agreement.md");
    md << "Camera " << camera << ", " << w << "x" << h << ", the Medium alone (no height fog); reference "
       << judge.reference_seconds()
       << " s.\n\n| renderer | quality | frame (ms) | mean error | p99 error | fog pixels |\n"
       << "|---|---|---|---|---|---|\n";
    for (const Rung& rung : ladder(c.quick())) {
        json varied = base;
        varied.merge_patch(rung.keys);
        judge.prepare(source.parse(varied), rung.mode);
        const double ms = judge.frame_ms(w, h, c.quick() ? 2 : 3);
        const render::FogError e = judge.error();
        const std::string series = render::to_string(rung.mode);
        render::write_png_atomic(c.out_dir() / ("agreement_" + series + ".png"), judge.last_image());
        c.add({series, rung.label, ms, ms / 1e3, "mean relative luminance error", e.mean_relative, 0.0, 0.0});
        md << "| " << series << " | " << rung.label << " | " << ms << " | " << e.mean_relative * 100 << " % | "
           << e.p99_relative * 100 << " % | " << e.fog_pixels << " |\n";
        std::printf("  %-9s %-14s %8.1f ms  mean %6.2f %%  p99 %6.2f %%\n", series.c_str(), rung.label.c_str(), ms,
                    e.mean_relative * 100, e.p99_relative * 100);
        std::fflush(stdout);
    }
}

}  // namespace

KIRI_BENCH_STAGE({"agreement",
                  "Fog renderers of the default scene's Medium: error against the CPU reference vs frame cost",
                  {"frame (ms)", "error_value", "mean relative luminance error", true, true, true},
                  agreement});

}  // namespace kiri::bench
