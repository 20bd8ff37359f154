// The layer stack: [Thesis] Table 3.2 reproduced on this machine (frames per
// second against tessellation and layer count at 1280x720), its figures as images (spacing
// rule, scale rule, 15 against 30 layers), the cost of off-screen fog, and the error of a
// finite stack against a very fine one.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>

#include "bench/bench.hpp"
#include "bench/layers_scene.hpp"
#include "kiri/render/image.hpp"

namespace kiri::bench {
namespace {

// Table 3.2 of the source (Athlon 1.33 GHz, Radeon 8500): FPS per tessellation and layer count.
const std::map<int, std::vector<double>> source_fps = {
    {4, {108, 80, 65, 55, 47, 42, 37, 34, 32}},
    {5, {81, 67, 55, 45, 40, 36, 31, 28, 27}},
    {8, {51, 38, 30, 26, 22, 19, 17, 15, 14}},
    {10, {39, 29, 23, 19, 16, 14, 12, 11, 10}},
};

void layers_figures(Context& c, LayerBenchScene& s)
{
    const int w = 960, h = 540;
    auto shot = [&](const LayerFog& fog, const render::Camera& camera, const std::string& name) {
        s.renderer->set_layers(*fog.base, fog.layers);
        render::write_png_atomic(c.out_dir() / name, s.renderer->render(camera, w, h));
    };
    {
        LayerFog fog = s.fog(8, 15);
        fog.layers.narrowing = false;
        shot(fog, s.side_near(), "layers_side_fixed_spacing.png");
        fog.layers.narrowing = true;
        shot(fog, s.side_near(), "layers_side_narrowed.png");
        // The source's case: a texture whose outline is sharp, seen from above, in the source's
        // shading (the medium shading leaves the enlargement out: layers_enlarge).
        LayerFog sharp = s.fog(8, 15, 0.06);
        sharp.layers.shading = geometry::LayerShading::source;
        sharp.layers.enlargement = false;
        shot(sharp, s.top(), "layers_top_no_scale.png");
        sharp.layers.enlargement = true;
        shot(sharp, s.top(), "layers_top_scaled.png");
    }
    for (int count : {15, 30}) {
        const LayerFog fog = s.fog(8, count);
        shot(fog, s.oblique(), "layers_" + std::to_string(count) + ".png");
    }
    std::printf("  figures: %s/layers_*.png\n", c.out_dir().string().c_str());
}

void layers_table(Context& c)
{
    LayerBenchScene s(c.data_dir());
    const int w = 1280, h = 720, frames = c.quick() ? 5 : 15;
    layers_figures(c, s);

    s.renderer->clear_layers();
    const double terrain_only = s.frame_seconds(s.oblique(), w, h, frames);
    const render::Image bare = s.renderer->render(s.oblique(), w, h);
    c.add({"terrain alone", "1280x720", 0.0, terrain_only, "", 0.0, 1.0 / terrain_only, 0.0});

    const std::vector<int> levels = c.quick() ? std::vector<int>{4, 10} : std::vector<int>{4, 5, 8, 10};
    std::vector<int> counts;
    for (int n = 10; n <= 50; n += c.quick() ? 20 : 5)
        counts.push_back(n);
    std::ofstream md(c.out_dir() / "layers_table.md");
    md << "Frames per second of the whole frame (sky, terrain, layers at half resolution, resolve) at 1280x720.\n\n";
    md << "| tessellation | layers | kiri FPS (this machine) | source FPS (Radeon 8500) | layers drawn | stack on screen |\n"
       << "|---|---|---|---|---|---|\n";
    for (int level : levels) {
        for (int count : counts) {
            LayerFog fog = s.fog(level, count);
            fog.layers.narrowing = false;  // the source's table: a fixed number of layers
            s.renderer->set_layers(*fog.base, fog.layers);
            const double t = s.frame_seconds(s.oblique(), w, h, frames);
            const int drawn = s.renderer->last_stats().layers;
            const double cover = changed_fraction(bare, s.renderer->render(s.oblique(), w, h));
            const std::string lv = std::to_string(level) + "x" + std::to_string(level);
            c.add({"kiri " + lv, "layers=" + std::to_string(count) + " cover=" + std::to_string(cover), double(count),
                   t, "", 0.0, 1.0 / t, 0.0});
            const double src = source_fps.at(level)[std::size_t((count - 10) / 5)];
            c.add({"source " + lv, "Radeon 8500", double(count), 1.0 / src, "", 0.0, src, 0.0});
            md << "| " << lv << " | " << count << " | " << std::lround(1.0 / t) << " | " << src << " | " << drawn + 1
               << " | " << std::lround(cover * 100) << " % |\n";
        }
    }
    // The hardest cell (10x10, 50 layers) drawn at full resolution into the multisampled
    // frame (the plain way) and at reduced resolution with depth-aware upsampling.
    {
        LayerFog fog = s.fog(10, 50);
        fog.layers.narrowing = false;
        s.renderer->set_layers(*fog.base, fog.layers);
        s.renderer->set_layer_resolution(1.0, true);
        const double t_plain = s.frame_seconds(s.oblique(), w, h, frames);
        const render::Image plain = s.renderer->render(s.oblique(), w, h);
        s.renderer->set_layer_resolution(1.0);
        const render::Image full = s.renderer->render(s.oblique(), w, h);
        md << "\nHardest cell (10x10, 50 layers); layer pass = frame - terrain alone; plain = the layers drawn straight "
              "into the 8-bit multisampled frame; full = the same at full resolution in a float target:\n\n"
           << "| layer pass | frame FPS | layer pass ms | layer pass FPS | mean difference to plain | to full (8-bit levels) |\n"
           << "|---|---|---|---|---|---|\n";
        const double plain_pass = std::max(t_plain - terrain_only, 1e-6);
        md << "| plain, multisampled | " << std::lround(1.0 / t_plain) << " | " << plain_pass * 1e3 << " | "
           << std::lround(1.0 / plain_pass) << " | 0 | " << mean_abs_difference(full, plain) << " |\n";
        c.add({"hardest cell, layer scale", "plain multisampled", 1.0, t_plain, "mean |image - plain| (8-bit levels)",
               0.0, 1.0 / t_plain, 0.0});
        for (double scale : {1.0, 0.5, 0.35, 0.25}) {
            s.renderer->set_layer_resolution(scale);
            const double t = s.frame_seconds(s.oblique(), w, h, frames);
            const render::Image image = s.renderer->render(s.oblique(), w, h);
            const double e = mean_abs_difference(plain, image), ef = mean_abs_difference(full, image);
            const double pass = std::max(t - terrain_only, 1e-6);
            c.add({"hardest cell, layer scale", "scale=" + std::to_string(scale), scale, t,
                   "mean |image - plain| (8-bit levels)", e, 1.0 / t, 0.0});
            md << "| scale " << scale << " | " << std::lround(1.0 / t) << " | " << pass * 1e3 << " | "
               << std::lround(1.0 / pass) << " | " << e << " | " << ef << " |\n";
        }
        s.renderer->set_layer_resolution(0.5);
    }
    // Culling: the same stack off-screen costs (almost) nothing over the terrain alone.
    LayerFog fog = s.fog(10, 50);
    s.renderer->set_layers(*fog.base, fog.layers);
    const double away_fog = s.frame_seconds(s.away(), w, h, frames);
    s.renderer->clear_layers();
    const double away_bare = s.frame_seconds(s.away(), w, h, frames);
    c.add({"fog off-screen", "10x10, 50 layers", 0.0, away_fog, "ratio to terrain alone", away_fog / away_bare,
           1.0 / away_fog, 0.0});
    md << "\nTerrain alone " << std::lround(1.0 / terrain_only) << " FPS; fog off-screen (10x10, 50 layers) costs "
       << (away_fog / away_bare - 1.0) * 100.0 << " % over the terrain alone.\n";
}

// The stack converges to a continuous medium as layers are added, each layer thinner
// (per-layer opacity 1 - (1 - o)^(15 / n), the alpha correction of the spacing rule).
void error_curve(Context& c)
{
    LayerBenchScene s(c.data_dir());
    const int w = 640, h = 360, frames = c.quick() ? 3 : 9;
    auto stack = [&](int count) {
        LayerFog fog = s.fog(8, count);
        fog.layers.narrowing = false;
        fog.layers.opacity = 1.0 - std::pow(1.0 - s.scene.layers.opacity, 15.0 / count);
        fog.layers.optics.detail = 0.0;  // the noise varies per layer; compare the medium itself
        fog.layers.enlargement = false;  // (2.10) grows with the layer index: 400 layers would be 40 % wider
        return fog;
    };
    const LayerFog fine = stack(400);
    s.renderer->set_layers(*fine.base, fine.layers);
    const render::Image limit = s.renderer->render(s.oblique(), w, h);
    for (int count : {5, 10, 15, 20, 30, 50, 80, 120, 200}) {
        if (c.quick() && count > 50)
            break;
        const LayerFog fog = stack(count);
        s.renderer->set_layers(*fog.base, fog.layers);
        const double t = s.frame_seconds(s.oblique(), w, h, frames);
        const double e = mean_abs_difference(limit, s.renderer->render(s.oblique(), w, h));
        c.add({"layers (640x360)", "layers=" + std::to_string(count), double(count), t,
               "mean |image - 400 layers| (8-bit levels)", e, 1.0 / t, 0.0});
    }
}

}  // namespace

KIRI_BENCH_STAGE({"layers",
                  "Layer stack at 1280x720: frames per second against layers (source: Table 3.2)",
                  {"layers", "items_per_s", "frames per second", false, true},
                  layers_table});
KIRI_BENCH_STAGE({"layers_error",
                  "Layer stack: image error against a 400-layer stack vs layer count",
                  {"layers", "error_value", "mean |difference| (8-bit levels)", true, true},
                  error_curve});

}  // namespace kiri::bench
