// Views: every renderer at its default quality judged against the CPU reference from many views,
// not one: the cameras of the shipped scenes (blanket, lake, fill, wind, the descent through the
// fog), an eye inside the fog, and terrains unlike Jacksboro (a canyon and a lone peak, written
// here as ESRI ASCII grids and given to kiri as bare DEMs, every key derived). The Medium alone,
// as the agreement stage judges it: the froxels' height fog is left out of every renderer and of
// the reference; and the default scene as users render it, its height fog kept, for the
// renderers that draw a height fog (the froxels, combined). Goals: each renderer alone 3 % mean;
// combined 2 % mean and 10 % p99.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "bench/bench.hpp"
#include "bench/fog_judge.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/medium/medium.hpp"
#include "kiri/geometry/scene/dem_scene.hpp"
#include "kiri/geometry/scene/pipeline.hpp"
#include "kiri/render/image.hpp"
#include "kiri/render/tone_map.hpp"

namespace kiri::bench {
namespace {

namespace fs = std::filesystem;

struct View {
    std::string label;  //!< scene/camera
    geometry::Scene scene;
    std::string camera;
    bool height_fog = false;  //!< the scene's height fog kept: only the froxels and combined draw it
};

// A DEM as an ESRI ASCII grid (metres, north up), height(x, y) with x, y in [0, 1].
fs::path write_ascii_grid(const fs::path& file, int nx, int ny, double cell,
                          const std::function<double(double, double)>& height)
{
    std::ofstream out(file);
    out << "ncols " << nx << "\nnrows " << ny << "\nxllcorner 0\nyllcorner 0\ncellsize " << cell
        << "\nNODATA_value -9999\n";
    for (int r = 0; r < ny; ++r) {
        for (int c = 0; c < nx; ++c)
            out << height(double(c) / (nx - 1), 1.0 - double(r) / (ny - 1)) << (c + 1 < nx ? " " : "\n");
    }
    return file;
}

// An eye inside the fog: halfway up the thickest column of the Medium, looking level towards the
// Medium's centre (or along x from the centre itself).
geometry::CameraSpec inside_camera(const geometry::Scene& scene)
{
    geometry::Pipeline pipeline;
    const geometry::PipelineProducts& p = pipeline.run(scene, {geometry::Stage::medium});
    const geometry::MediumGrid& g = p.medium->grid();
    std::size_t best = 0;
    double thickest = -1.0;
    for (std::size_t k = 0; k < g.floor.size(); ++k) {
        const double t = g.coverage[k] * (g.top[k] - g.floor[k]);
        if (t > thickest)
            thickest = t, best = k;
    }
    const int i = int(best % std::size_t(g.nx)), j = int(best / std::size_t(g.nx));
    const glm::dvec3 eye(g.x0 + i * g.dx, g.y0 + j * g.dy, g.floor[best] + 0.5 * (g.top[best] - g.floor[best]));
    const geometry::Bounds3& b = p.medium->bounds();
    glm::dvec2 towards = 0.5 * (glm::dvec2(b.min) + glm::dvec2(b.max)) - glm::dvec2(eye);
    if (glm::length(towards) < 1.0)
        towards = {1.0, 0.0};
    towards = glm::normalize(towards);
    return {"inside", eye, eye + glm::dvec3(towards * 2000.0, 0.0), 60.0};
}

geometry::Scene medium_alone(geometry::Scene s)
{
    s.froxel.height_fog = {};
    return s;
}

std::vector<View> views(Context& c)
{
    std::vector<View> v;
    const fs::path scenes = c.data_dir() / "scenes";
    // Quick: a camera of each kind; full: every camera of every shipped scene.
    const std::vector<std::pair<std::string, std::vector<std::string>>> quick = {
        {"jacksboro", {"default", "ridge", "top"}},
        {"jacksboro_descent", {"descent_3_inside"}},
        {"jacksboro_lake", {"default"}},
        {"jacksboro_fill", {"valley"}},
        {"jacksboro_wind", {"default"}}};
    for (const auto& [name, cameras] : quick) {
        const geometry::Scene s = medium_alone(geometry::load_scene(scenes / (name + ".json")));
        if (c.quick()) {
            for (const std::string& cam : cameras)
                v.push_back({name + "/" + cam, s, cam});
        } else {
            for (const geometry::CameraSpec& cam : s.cameras)
                v.push_back({name + "/" + cam.name, s, cam.name});
        }
    }
    // The lake as a dense fog (10 m of visibility, 0.39 per metre): its light comes from a sunlit
    // skin a few metres deep, thinner than a layer's slab, a march's step or a froxel.
    geometry::Scene dense = medium_alone(geometry::load_scene(scenes / "jacksboro_lake.json"));
    dense.medium.extinction = geometry::extinction_from_visibility(10.0);
    v.push_back({"jacksboro_lake_dense/default", dense, "default"});
    // The default scene as users render it: its height fog (a dense haze in the valleys) too.
    const geometry::Scene with_haze = geometry::load_scene(scenes / "jacksboro.json");
    for (const char* cam : {"default", "top"})
        v.push_back({std::string("jacksboro_with_height_fog/") + cam, with_haze, cam, true});
    const fs::path dir = c.out_dir() / "views";
    fs::create_directories(dir);
    const auto dem = [&](const std::string& name, int nx, int ny, double cell,
                         const std::function<double(double, double)>& height) {
        geometry::Scene s =
            medium_alone(geometry::dem_scene(write_ascii_grid(dir / (name + ".asc"), nx, ny, cell, height)));
        v.push_back({name + "/derived", s, ""});
        s.cameras.push_back(inside_camera(s));
        v.push_back({name + "/inside", s, "inside"});
    };
    // A meandering canyon 300 m deep in a plateau rising northwards (10 m cells).
    dem("canyon", 240, 180, 10.0, [](double x, double y) {
        const double axis = 0.5 + 0.1 * std::sin(6.0 * y);
        return 900.0 - 300.0 * std::exp(-(x - axis) * (x - axis) / 0.008) + 60.0 * y +
            20.0 * std::sin(9.0 * x + 3.0 * y);
    });
    // A lone peak 900 m above a rippled plain (30 m cells).
    dem("peak", 200, 200, 30.0, [](double x, double y) {
        const double r2 = (x - 0.5) * (x - 0.5) + (y - 0.5) * (y - 0.5);
        return 300.0 + 900.0 * std::exp(-r2 / (2.0 * 0.16 * 0.16)) + 30.0 * std::sin(20.0 * x) * std::cos(17.0 * y);
    });
    return v;
}

void views_stage(Context& c)
{
    const int w = c.quick() ? 160 : 320, h = c.quick() ? 90 : 180;
    const render::FogMode modes[] = {render::FogMode::layers, render::FogMode::particles, render::FogMode::froxel,
                                     render::FogMode::combined};
    // The views `kiri bench --view` named, before anything is written of them: a text that names
    // none is an error, and the DEMs views() wrote go with it.
    std::vector<View> chosen;
    std::string labels;
    for (View& view : views(c)) {
        labels += (labels.empty() ? "" : ", ") + view.label;
        if (c.wants_view(view.label))
            chosen.push_back(std::move(view));
    }
    if (chosen.empty()) {
        std::error_code ec;
        for (const char* dem : {"canyon.asc", "peak.asc"})
            fs::remove(c.out_dir() / "views" / dem, ec);
        fs::remove(c.out_dir() / "views", ec);  // only if it is empty now
        throw InputError("", "--view", "names none of the views (" + labels + ")");
    }
    std::ofstream md(c.out_dir() / "views.md");
    md << w << "x" << h << ", the Medium alone (no height fog; the views with_height_fog keep the scene's, which only "
       << "the froxels and combined draw), every renderer at its default quality; mean / p99 "
       << "relative luminance error against the CPU reference.\n\n| view | reference (s) | fog pixels |";
    for (render::FogMode m : modes)
        md << " " << render::to_string(m) << " |";
    md << "\n|---|---|---|---|---|---|---|\n";
    int index = 0;
    std::vector<double> worst(std::size(modes), 0.0);
    for (const View& view : chosen) {
        FogJudge judge(view.scene, view.camera, w, h);
        std::string safe = view.label;
        std::replace(safe.begin(), safe.end(), '/', '_');
        render::write_png_atomic(c.out_dir() / "views" / (safe + "_reference.png"),
                                 render::tone_mapped(judge.reference()));
        md << "| " << view.label << " | " << judge.reference_seconds() << " |";
        std::printf("  %-34s reference %5.1f s", view.label.c_str(), judge.reference_seconds());
        int fog_pixels = -1;
        std::string cells;
        for (std::size_t m = 0; m < std::size(modes); ++m) {
            if (view.height_fog && (modes[m] == render::FogMode::layers || modes[m] == render::FogMode::particles)) {
                cells += " - |";  // they do not draw a height fog
                continue;
            }
            judge.prepare(view.scene, modes[m]);
            std::vector<float> signed_error;
            const render::FogError e = judge.error(&signed_error);
            fog_pixels = e.fog_pixels;
            const std::string series = render::to_string(modes[m]);
            render::write_png_atomic(c.out_dir() / "views" / (safe + "_" + series + ".png"), judge.last_image());
            // Where it errs: red brighter than the reference, blue darker, full at +-20 %.
            render::write_png_atomic(c.out_dir() / "views" / (safe + "_" + series + "_error.png"),
                                     render::error_map(signed_error, w, h));
            c.add({series, view.label, double(index), 0.0, "mean relative luminance error", e.mean_relative, 0.0, 0.0});
            char cell[64];
            std::snprintf(cell, sizeof cell, " %.2f / %.1f %% |", e.mean_relative * 100, e.p99_relative * 100);
            cells += cell;
            std::printf("  %s %.2f/%.1f %%", series.c_str(), e.mean_relative * 100, e.p99_relative * 100);
            worst[m] = std::max(worst[m], e.mean_relative);
        }
        md << " " << fog_pixels << " |" << cells << "\n";
        std::printf("\n");
        std::fflush(stdout);
        ++index;
    }
    md << "\nWorst mean:";
    for (std::size_t m = 0; m < std::size(modes); ++m)
        md << " " << render::to_string(modes[m]) << " " << worst[m] * 100 << " %"
           << (m + 1 < std::size(modes) ? ";" : ".\n");
}

}  // namespace

KIRI_BENCH_STAGE({"views",
                  "Every renderer at its default quality from many views and terrains: error against the CPU reference",
                  {"view", "error_value", "mean relative luminance error", false, true, true},
                  views_stage});

}  // namespace kiri::bench
