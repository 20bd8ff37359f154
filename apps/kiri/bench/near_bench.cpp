// Near: the particles' billboards near the eye drawn at a coarser resolution
// (particles.near_scale). The default scene from its first camera and from the frame stage's
// valley view (the eye inside the fog), in particles and combined mode: per setting of
// near_scale and near_pixels (near_scale 1: every billboard at full resolution), the particles pass's device time, the
// fragments the billboards blended and the error against the CPU reference, the settings
// alternated frame set by frame set so that each meets the same load. --quick: 640x360; else
// 1280x720.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "bench/bench.hpp"
#include "bench/fog_judge.hpp"
#include "bench/valley_view.hpp"

namespace kiri::bench {
namespace {

double particles_ms(const FrameCost& cost)
{
    for (const render::PassTime& p : cost.passes)
        if (p.pass == "particles")
            return p.gpu_ms;
    return 0.0;
}

void near(Context& c)
{
    SceneJson source(c.data_dir() / "scenes/jacksboro.json");
    nlohmann::json medium_only = source.root;
    medium_only["froxel"].erase("height_fog");
    geometry::Scene judged = source.parse(medium_only);
    geometry::Scene scene = source.parse(source.root);
    const geometry::CameraSpec valley = valley_camera(scene);
    judged.cameras.push_back(valley);
    const int w = c.quick() ? 640 : 1280, h = c.quick() ? 360 : 720;
    const int ew = c.quick() ? 160 : 320, eh = c.quick() ? 90 : 180;
    const int rounds = c.quick() ? 3 : 5, frames = 2;
    struct Setting {
        int scale;
        double pixels;
    };
    const Setting settings[] = {{1, 32.0}, {2, 32.0}, {2, 16.0}, {4, 32.0}};
    std::ofstream md(c.out_dir() / "near.md");
    md << "Particles pass: median over " << rounds << " alternated rounds of the median of " << frames
       << " moving frames at " << w << "x" << h << "; error: mean relative luminance against the CPU reference at "
       << ew << "x" << eh
       << ".\n\n| view | mode | near_scale | near_pixels | particles pass (ms) | / full | fragments | near "
       << "billboards | mean error | p99 error |\n|---|---|---|---|---|---|---|---|---|---|\n";
    for (const char* view : {"default", "valley"}) {
        FogJudge judge(judged, view == std::string("default") ? "" : view, ew, eh);
        for (render::FogMode mode : {render::FogMode::particles, render::FogMode::combined}) {
            std::vector<geometry::Scene> variants;
            for (const Setting& s : settings) {
                nlohmann::json j = medium_only;
                j["particles"]["near_scale"] = s.scale;
                j["particles"]["near_pixels"] = s.pixels;
                variants.push_back(source.parse(j));
                variants.back().cameras.push_back(valley);
            }
            std::vector<std::vector<double>> ms(std::size(settings));
            std::vector<FrameCost> last(std::size(settings));
            for (int r = 0; r < rounds; ++r)
                for (std::size_t k = 0; k < std::size(settings); ++k) {
                    judge.prepare(variants[k], mode);
                    last[k] = judge.frame_cost(w, h, frames);
                    ms[k].push_back(particles_ms(last[k]));
                }
            double full = 0.0;
            for (std::size_t k = 0; k < std::size(settings); ++k) {
                std::sort(ms[k].begin(), ms[k].end());
                const double median = ms[k][ms[k].size() / 2];
                if (k == 0)
                    full = median;
                judge.prepare(variants[k], mode);
                const render::FogError e = judge.error();
                const std::string m = render::to_string(mode);
                std::printf(
                    "  %-7s %-9s near_scale %d near_pixels %3.0f  particles %8.1f ms (%4.2f x full)  %10llu fragments  %5d "
                    "near  mean %5.2f %%  p99 %6.2f %%\n",
                    view, m.c_str(), settings[k].scale, settings[k].pixels, median, median / full,
                    (unsigned long long)last[k].particle_fragments, last[k].near_particles, e.mean_relative * 100,
                    e.p99_relative * 100);
                std::fflush(stdout);
                md << "| " << view << " | " << m << " | " << settings[k].scale << " | " << settings[k].pixels << " | "
                   << median << " | " << median / full << " | " << last[k].particle_fragments << " | "
                   << last[k].near_particles << " | " << e.mean_relative * 100 << " % | " << e.p99_relative * 100
                   << " % |\n";
                c.add({std::string(view) + " " + m,
                       "near_scale=" + std::to_string(settings[k].scale) +
                           " near_pixels=" + std::to_string(int(settings[k].pixels)),
                       double(settings[k].scale), median / 1e3, "mean relative luminance error", e.mean_relative, 0.0,
                       0.0});
            }
        }
    }
}

}  // namespace

KIRI_BENCH_STAGE({"near",
                  "Particles: billboards near the eye at a coarser resolution: pass time and error",
                  {"near_scale", "time_s", "particles pass (s)", true, false, true},
                  near});

}  // namespace kiri::bench
