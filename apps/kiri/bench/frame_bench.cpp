// Frame: what the fog costs on top of the terrain under it. The default scene as users render
// it (its height fog included) from its first camera and from a held-out view low in a valley,
// inside the fog, in every mode: per pass the device time, the frame's fog cost (the frame less
// the terrain-only frame of the same view, measured in the same run) as a ratio to that
// terrain-only frame, the time of a still picture as kiri render draws it, and the error against
// the CPU reference (of the Medium alone, as the agreement stage judges it: the height fog is
// drawn by the froxels only). --quick: 640x360; else 1280x720 and 1920x1080. Last, the preview's
// moving frame at its floor against the same frame drawn whole.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench.hpp"
#include "bench/fog_judge.hpp"
#include "bench/valley_view.hpp"
#include "kiri/geometry/medium/medium.hpp"
#include "kiri/geometry/terrain/terrain.hpp"
#include "kiri/render/fog_error.hpp"
#include "kiri/render/image.hpp"

namespace kiri::bench {
namespace {

constexpr render::FogMode modes[] = {render::FogMode::terrain, render::FogMode::layers, render::FogMode::particles,
                                     render::FogMode::froxel, render::FogMode::combined};

struct MeasuredMode {
    render::FogMode mode;
    FrameCost cost;
    double still_ms = 0.0;
    render::FogError error;
};

std::string passes_line(const FrameCost& cost)
{
    std::ostringstream s;
    s.precision(3);
    for (const render::PassTime& p : cost.passes)
        s << (s.tellp() > 0 ? ", " : "") << p.pass << ' ' << p.gpu_ms;
    if (cost.marched >= 0.0)
        s << "; froxel apply marched " << 100.0 * cost.marched << " % of the pixels, took their samples' mean at "
          << 100.0 * cost.upsampled << " %";
    if (cost.particle_fragments > 0)
        s << "; particles blended " << cost.particle_fragments << " fragments, " << cost.drawn_particles
          << " billboards in view, " << cost.near_particles << " of them near";
    return s.str();
}

// The preview while the view moves, at its floor, an eighth of a 1280x720 window (apps/preview
// frame_budget.hpp): the default mode and view at 160x90 as a still is drawn (the whole terrain
// grid, the options' froxel volume, the whole shell) and as a moving frame is (all three at an
// eighth), side by side, with their error against the reference at that size.
void moving_frames(Context& c, const geometry::Scene& scene, const geometry::Scene& judged, int frames,
                   std::ostream& md)
{
    FogJudge judge(judged, "", 160, 90);
    md << "\nThe preview while the view moves, at its floor (160x90, an eighth of 1280x720), combined, default view, "
       << "error against the CPU reference at 160x90:\n\n"
       << "| frame | time (ms) | frames a second | mean error | passes (device ms) |\n|---|---|---|---|---|\n";
    for (const double scale : {1.0, 0.125}) {
        judge.prepare(scene, render::FogMode::combined);
        judge.set_reduced_resolution(scale);
        const FrameCost cost = judge.frame_cost(160, 90, frames);
        judge.prepare(judged, render::FogMode::combined);
        const render::FogError error = judge.error();
        const char* name = scale < 1.0 ? "moving (grid, froxel volume, shell at 1/8)" : "whole grid, volume and shell";
        std::printf(
            "  preview floor 160x90, %-44s frame %7.1f ms = %5.1f a second (%d frames)  mean %5.2f %%\n    %s\n", name,
            cost.frame_ms, 1e3 / cost.frame_ms, cost.frames, 100.0 * error.mean_relative, passes_line(cost).c_str());
        md << "| " << name << " | " << cost.frame_ms << " | " << 1e3 / cost.frame_ms << " | "
           << 100.0 * error.mean_relative << " % | " << passes_line(cost) << " |\n";
        c.add({"preview floor 160x90", name, scale, cost.frame_ms / 1e3, "mean relative luminance error at 160x90",
               error.mean_relative, 0.0, 0.0});
    }
    judge.set_reduced_resolution(1.0);
}

struct FrameScenes {
    geometry::Scene scene, judged;  // as users render it; its Medium alone, as the reference judges it
};

FrameScenes default_scene(Context& c)
{
    SceneJson source(c.data_dir() / "scenes/jacksboro.json");
    nlohmann::json medium_only = source.root;
    medium_only["froxel"].erase("height_fog");
    return {source.parse(source.root), source.parse(medium_only)};
}

void frame(Context& c)
{
    auto [scene, judged] = default_scene(c);
    const geometry::CameraSpec valley = valley_camera(scene);
    scene.cameras.push_back(valley);
    judged.cameras.push_back(valley);
    std::printf("  valley view: eye %.0f %.0f %.0f, target %.0f %.0f %.0f\n", valley.position.x, valley.position.y,
                valley.position.z, valley.target.x, valley.target.y, valley.target.z);

    std::vector<std::pair<int, int>> sizes = {{640, 360}};
    if (!c.quick())
        sizes = {{1280, 720}, {1920, 1080}};
    const int ew = c.quick() ? 160 : 320, eh = c.quick() ? 90 : 180;
    const int frames = c.quick() ? 2 : 3;
    std::ofstream md(c.out_dir() / "frame.md");
    std::ostringstream passes_md;
    md << "Fog cost = frame - terrain-only frame of the same view and size, measured in the same run; error: "
       << "mean relative luminance against the CPU reference at " << ew << "x" << eh
       << " (the Medium alone). Still: a picture as kiri render draws it.\n\n"
       << "| size | view | mode | frame (ms) | fog cost (ms) | fog cost / terrain | still (ms) | mean error | "
          "p99 error |\n|---|---|---|---|---|---|---|---|---|\n";
    passes_md << "\n| size | view | mode | pass | device (ms) | issue (ms) |\n|---|---|---|---|---|---|\n";
    std::ostringstream device_md;
    for (const char* view : {"default", "valley"}) {
        const std::string camera = view == std::string("default") ? "" : view;
        FogJudge judge(judged, camera, ew, eh);
        std::printf("  %s view: reference %dx%d %.1f s\n", view, ew, eh, judge.reference_seconds());
        if (view == std::string("default")) {
            std::printf("  drawn by %s\n", judge.gl_description().c_str());
            device_md << "\nDrawn by " << judge.gl_description() << ".\n";
        }
        for (const auto& [w, h] : sizes) {
            const std::string size = std::to_string(w) + "x" + std::to_string(h);
            std::vector<MeasuredMode> rows;
            for (render::FogMode mode : modes) {
                MeasuredMode m{mode};
                judge.prepare(scene, mode);
                m.cost = judge.frame_cost(w, h, frames);
                m.still_ms = judge.still_ms(w, h);
                if (mode == render::FogMode::terrain) {
                    render::write_png_atomic(c.out_dir() / ("frame_" + std::string(view) + "_terrain.png"),
                                             judge.still_image());
                } else {
                    render::write_png_atomic(
                        c.out_dir() / ("frame_" + std::string(view) + "_" + render::to_string(mode) + ".png"),
                        judge.still_image());
                    judge.prepare(judged, mode);
                    std::vector<float> signed_error;
                    m.error = judge.error(&signed_error);
                    render::write_png_atomic(
                        c.out_dir() / ("frame_" + std::string(view) + "_" + render::to_string(mode) + "_error.png"),
                        render::error_map(signed_error, ew, eh));
                }
                rows.push_back(m);
            }
            const double terrain_ms = rows.front().cost.frame_ms;
            for (const MeasuredMode& m : rows) {
                const std::string mode = render::to_string(m.mode);
                const double fog_ms = m.cost.frame_ms - terrain_ms, ratio = fog_ms / terrain_ms;
                const bool fog = m.mode != render::FogMode::terrain;
                std::printf("  %-9s %-7s %-9s frame %8.1f ms  fog %8.1f ms = %5.2f x terrain  still %8.1f ms",
                            size.c_str(), view, mode.c_str(), m.cost.frame_ms, fog_ms, ratio, m.still_ms);
                if (fog)
                    std::printf("  mean %5.2f %%  p99 %6.2f %%", m.error.mean_relative * 100,
                                m.error.p99_relative * 100);
                std::printf("  (%d frames)\n    %s\n", m.cost.frames, passes_line(m.cost).c_str());
                std::fflush(stdout);
                md << "| " << size << " | " << view << " | " << mode << " | " << m.cost.frame_ms << " | ";
                if (fog)
                    md << fog_ms << " | " << ratio << " | ";
                else
                    md << "- | - | ";
                md << m.still_ms << " | ";
                if (fog)
                    md << m.error.mean_relative * 100 << " % | " << m.error.p99_relative * 100 << " % |\n";
                else
                    md << "- | - |\n";
                for (const render::PassTime& p : m.cost.passes)
                    passes_md << "| " << size << " | " << view << " | " << mode << " | " << p.pass << " | " << p.gpu_ms
                              << " | " << p.cpu_ms << " |\n";
                if (fog)
                    c.add({std::string(view) + " " + size, mode, ratio, m.cost.frame_ms / 1e3,
                           "mean relative luminance error at " + std::to_string(ew) + "x" + std::to_string(eh),
                           m.error.mean_relative, 0.0, 0.0});
            }
        }
    }
    md << device_md.str() << passes_md.str();
    moving_frames(c, scene, judged, 2 * frames + 1, md);
}

// The floor alone, over many frames (a moving frame at the floor is short and noisy).
void floor_stage(Context& c)
{
    const auto [scene, judged] = default_scene(c);
    std::ofstream md(c.out_dir() / "floor.md");
    moving_frames(c, scene, judged, c.quick() ? 20 : 40, md);
}

}  // namespace

KIRI_BENCH_STAGE({"frame",
                  "The fog's cost per frame against the terrain-only frame, and its error against the CPU reference",
                  {"fog cost / terrain-only frame", "error_value", "mean relative luminance error", false, false, true},
                  frame});

KIRI_BENCH_STAGE(
    {"floor",
     "The preview's moving frame at its floor (160x90) against the same frame drawn whole, and their error",
     {"froxel volume, grid and shell scale", "time_s", "frame (s)", true, false, true},
     floor_stage});

}  // namespace kiri::bench
