// Particle clouds: [Shimada08] Table 1 reproduced on this machine (precompute time of
// Harris's light pass and of the 3D attenuation buffer at 128^3 / 256^3 / 384^3 for 9,382 /
// 32,914 / 60,134 particles, with each one's per-particle error against the exact Harris pass),
// the goal at 60,134 particles and 128^3, the resolution against error and time, the error
// against the optical depth per voxel, and the figures.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>

#include "bench/bench.hpp"
#include "bench/particles_scene.hpp"
#include "bench/report.hpp"
#include "kiri/geometry/particles/harris_reference.hpp"
#include "kiri/geometry/scene/pipeline.hpp"
#include "kiri/geometry/terrain/terrain.hpp"
#include "kiri/render/attenuation.hpp"
#include "kiri/render/renderer.hpp"

namespace kiri::bench {
namespace {

// Table 1 of [Shimada08] (GeForce 8800 GTX, Core 2 Duo 1.83 GHz), seconds.
const std::map<std::size_t, double> paper_harris = {{9382, 0.721}, {32914, 3.164}, {60134, 5.934}};
const std::map<int, std::map<std::size_t, double>> paper_buffer = {
    {384, {{9382, 0.038}, {32914, 0.154}, {60134, 0.161}}},
    {256, {{9382, 0.015}, {32914, 0.044}, {60134, 0.055}}},
    {128, {{9382, 0.007}, {32914, 0.015}, {60134, 0.016}}}};

constexpr int harris_buffer = 512;  // Harris's light buffer, pixels a side

double seconds_since(std::chrono::steady_clock::time_point t)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

std::string fixed(double v, int digits)
{
    char s[64];
    std::snprintf(s, sizeof s, "%.*f", digits, v);
    return s;
}

void particles_figures(Context& c, ParticleBenchScene& s)
{
    const geometry::Terrain terrain = geometry::load_scene_terrain(s.scene);
    render::Renderer r;
    r.set_terrain(terrain);
    render::SunLight sun{s.scene.sun.direction, s.scene.sun.color, s.scene.sun.intensity, s.scene.sun.ambient};
    r.set_sun(sun);
    render::Camera cam;
    // From the east, looking towards the low western sun past the cloud: its sunlit rim and top
    // bright, its body and underside in its own shadow.
    cam.position = {8500.0, -2500.0, 2700.0};
    cam.target = {0.0, 0.0, 2350.0};
    cam.fov_y_deg = 30.0;
    const geometry::Medium m = ParticleBenchScene::cumulus();
    for (std::size_t n : shimada_counts) {
        if (c.quick() && n > 9382)
            break;
        const geometry::ParticleCloud cloud = ParticleBenchScene::sample(m, n);
        r.set_particles(cloud);
        render::write_png_atomic(c.out_dir() / ("particles_cumulus_" + std::to_string(n) + ".png"),
                                 r.render(cam, 960, 540));
    }
    // The last cloud from the south-south-west, across the light: the sun (west-north-west, 19
    // degrees up) from the left, so its top and left are lit and its right and underside lie in
    // its own shadow.
    render::Camera side = cam;
    side.position = {-3800.0, -8150.0, 2300.0};
    side.target = {0.0, 0.0, 2300.0};
    render::write_png_atomic(c.out_dir() / "particles_cumulus_side.png", r.render(side, 960, 540));
    // The default scene's fog as particles, from its camera and towards the sun.
    const geometry::PipelineProducts fog =
        geometry::author_scene(s.scene, {geometry::Stage::particles, geometry::ParticleSet::whole});
    const geometry::ParticleCloud& cloud = *fog.particles;
    r.set_particles(cloud);
    const geometry::CameraSpec spec = s.scene.camera("", terrain.bounds().min, terrain.bounds().max);
    render::Camera view;
    view.position = spec.position;
    view.target = spec.target;
    view.fov_y_deg = spec.fov_y_deg;
    render::write_png_atomic(c.out_dir() / "particles_jacksboro.png", r.render(view, 960, 540));
    view.position = {9000.0, -6000.0, 2500.0};
    view.target = {-2000.0, 1000.0, 700.0};
    view.fov_y_deg = 50.0;
    render::write_png_atomic(c.out_dir() / "particles_jacksboro_sunward.png", r.render(view, 960, 540));
    std::printf("  figures: %s/particles_*.png\n", c.out_dir().string().c_str());
}

// The goal, measured in pairs: Harris's pass and the buffer's builds one after the other, so both
// meet the same load on this shared machine (the read-back latency Harris pays swings with it);
// the median of the rounds' ratios decides.
void goal(Context& c, ParticleBenchScene& s, const geometry::Medium& m, std::size_t n, std::ofstream& md)
{
    const geometry::ParticleCloud cloud = ParticleBenchScene::sample(m, n);
    const std::vector<double> exact = geometry::harris_light_pass(cloud, s.sun);
    render::AttenuationBuffer b;
    b.set_particles(cloud);
    render::AttenuationOptions o;  // 128^3, R16F
    std::vector<double> ratios, harris, buffer;
    GammaError error;
    double harris_error = 0.0;
    for (int round = 0; round < (c.quick() ? 1 : 5); ++round) {
        render::HarrisGlStats hs;
        harris_error = relative_error(render::harris_light_pass_gl(cloud, s.sun, harris_buffer, &hs), exact).mean;
        const BufferBuild r = time_buffer(b, s.sun, o, 5, exact);
        error = r.error;
        harris.push_back(hs.seconds);
        buffer.push_back(r.best_s);
        ratios.push_back(hs.seconds / r.best_s);
        c.add({"goal rounds: Harris GL 512^2 / buffer 128^3", "round=" + std::to_string(round), double(n), r.best_s,
               "speed-up over Harris GL", ratios.back(), 0.0, 0.0});
    }
    std::vector<double> sorted = ratios;
    std::sort(sorted.begin(), sorted.end());
    const double median = sorted[sorted.size() / 2];
    md << "\nGoal at " << n << " particles and 128^3, " << ratios.size()
       << " rounds of Harris's GL pass (512^2) then 5 builds of the buffer:\n\n"
       << "| round | Harris (s) | buffer, best of 5 (ms) | speed-up |\n|---|---|---|---|\n";
    for (std::size_t k = 0; k < ratios.size(); ++k)
        md << "| " << k + 1 << " | " << fixed(harris[k], 3) << " | " << fixed(buffer[k] * 1e3, 1) << " | "
           << fixed(ratios[k], 0) << "x |\n";
    md << "\nMedian speed-up " << fixed(median, 0) << "x (range " << fixed(sorted.front(), 0) << "x .. "
       << fixed(sorted.back(), 0) << "x), mean relative error " << fixed(error.mean * 100, 2)
       << " % (Harris's own: " << fixed(harris_error * 100, 2)
       << " %); goal >= 100x and <= 1 %: " << (median >= 100.0 && error.mean <= 0.01 ? "met" : "NOT met") << ".\n";
    std::printf(
        "  goal (%zu particles, 128^3): median %.0fx faster than Harris GL (%.0fx .. %.0fx), mean error %.2f %%\n", n,
        median, sorted.front(), sorted.back(), error.mean * 100);
}

void particles_table(Context& c)
{
    ParticleBenchScene s(c.data_dir());
    particles_figures(c, s);
    const geometry::Medium m = ParticleBenchScene::cumulus();
    const int repeats = c.quick() ? 3 : 7;
    std::vector<std::size_t> counts(std::begin(shimada_counts), std::end(shimada_counts));
    if (c.quick())
        counts.resize(2);
    std::ofstream md(c.out_dir() / "particles_table.md");
    md << "Precompute (light pass) times in seconds, this machine beside Shimada's Table 1 (GeForce 8800 GTX); "
          "error = mean relative error of Gamma per particle against the exact Harris pass (max in brackets). "
          "Buffer: R16F, best of "
       << repeats << " builds (median in brackets).\n\n"
       << "| method | 9,382 | 32,914 | 60,134 |\n|---|---|---|---|\n";
    std::map<std::string, std::map<std::size_t, std::string>> cells;
    std::map<std::size_t, double> harris_s, harris_error;
    std::map<std::pair<int, std::size_t>, BufferBuild> builds;
    for (std::size_t n : counts) {
        auto t0 = std::chrono::steady_clock::now();
        const geometry::ParticleCloud cloud = ParticleBenchScene::sample(m, n);
        const double sample_s = seconds_since(t0);
        t0 = std::chrono::steady_clock::now();
        geometry::HarrisStats stats;
        const std::vector<double> exact = geometry::harris_light_pass(cloud, s.sun, &stats);
        const double exact_s = seconds_since(t0);
        double mean_log = 0.0;
        for (double g : exact)
            mean_log += std::log(g);
        std::printf(
            "  %zu particles: sampled in %.2f s (spacing %.1f m), exact pass %.2f s (%zu occluders, mean log Gamma %.2f)\n",
            n, sample_s, cloud.spacing, exact_s, stats.occluders, mean_log / double(n));
        c.add({"exact Harris, CPU double (this machine)", "N=" + std::to_string(n), double(n), exact_s, "", 0.0,
               double(n) / exact_s, 0.0});
        cells["exact Harris pass, CPU, double, light-plane index (this machine)"][n] = fixed(exact_s, 3);
        // Harris on the GPU, the paper's "Harris" row: a 512^2 light buffer (as accurate as the
        // attenuation buffer at 128^3), best of three runs (one in quick mode); and one with pixels
        // of a quarter of the smallest radius (faster, coarser).
        render::HarrisGlStats hs;
        std::vector<float> gl;
        double gl_s = 1e300;
        for (int k = 0; k < (c.quick() ? 1 : 3); ++k) {
            gl = render::harris_light_pass_gl(cloud, s.sun, harris_buffer, &hs);
            gl_s = std::min(gl_s, hs.seconds);
        }
        harris_s[n] = gl_s;
        harris_error[n] = relative_error(gl, exact).mean;
        const GammaError ge = relative_error(gl, exact);
        c.add({"Harris GL light pass, 512^2 (this machine)", "N=" + std::to_string(n), double(n), gl_s,
               "mean relative error", ge.mean, double(n) / gl_s, 0.0});
        c.add({"Harris (paper, 8800 GTX)", "N=" + std::to_string(n), double(n), paper_harris.at(n), "", 0.0, 0.0, 0.0});
        cells["Harris, GL 512^2 light buffer + one read-back per particle (this machine)"][n] =
            fixed(gl_s, 3) + " (error " + fixed(ge.mean * 100, 2) + " %)";
        render::HarrisGlStats coarse_stats;
        const GammaError coarse = relative_error(render::harris_light_pass_gl(cloud, s.sun, 0, &coarse_stats), exact);
        cells["Harris, GL light buffer of r_min / 4 pixels (this machine)"][n] = fixed(coarse_stats.seconds, 3) + " (" +
            std::to_string(coarse_stats.buffer_size) + "^2, error " + fixed(coarse.mean * 100, 2) + " %)";
        cells["Harris (paper)"][n] = fixed(paper_harris.at(n), 3);
        render::AttenuationBuffer b;
        b.set_particles(cloud);
        for (int res : {384, 256, 128}) {
            if (c.quick() && res == 384)
                continue;
            render::AttenuationOptions o;
            o.resolution = res;
            const BufferBuild r = time_buffer(b, s.sun, o, repeats, exact);
            builds[{res, n}] = r;
            const std::string rs = std::to_string(res);
            c.add({"buffer " + rs + "^3 (this machine)",
                   "N=" + std::to_string(n) + " mib=" + fixed(r.bytes / 1048576.0, 0), double(n), r.best_s,
                   "mean relative error", r.error.mean, double(n) / r.best_s, 0.0});
            c.add({"buffer " + rs + "^3 (paper)", "N=" + std::to_string(n), double(n), paper_buffer.at(res).at(n), "",
                   0.0, 0.0, 0.0});
            cells["attenuation buffer " + rs + "^3 (this machine)"][n] = fixed(r.best_s, 4) + " [" +
                fixed(r.median_s, 4) + "] (error " + fixed(r.error.mean * 100, 2) + " % [" +
                fixed(r.error.max * 100, 1) + " %])";
            cells["proposed " + rs + "^3 (paper)"][n] = fixed(paper_buffer.at(res).at(n), 3);
            std::printf(
                "  %zu particles, %d^3: %.1f ms (setup %.1f, deposit %.1f, scan %.1f, upload %.1f), error %.3f %% (max %.1f %%), %.0f MiB\n",
                n, res, r.best_s * 1e3, r.times.setup_ms, r.times.deposit_ms, r.times.scan_ms, r.times.upload_ms,
                r.error.mean * 100, r.error.max * 100, r.bytes / 1048576.0);
        }
    }
    for (const std::string& row :
         {std::string("Harris (paper)"),
          std::string("Harris, GL 512^2 light buffer + one read-back per particle (this machine)"),
          std::string("Harris, GL light buffer of r_min / 4 pixels (this machine)"),
          std::string("exact Harris pass, CPU, double, light-plane index (this machine)"),
          std::string("proposed 384^3 (paper)"), std::string("attenuation buffer 384^3 (this machine)"),
          std::string("proposed 256^3 (paper)"), std::string("attenuation buffer 256^3 (this machine)"),
          std::string("proposed 128^3 (paper)"), std::string("attenuation buffer 128^3 (this machine)")}) {
        md << "| " << row;
        for (std::size_t n : shimada_counts)
            md << " | " << (cells[row].count(n) ? cells[row][n] : "");
        md << " |\n";
    }
    goal(c, s, m, counts.back(), md);
    std::printf("  table: %s\n", (c.out_dir() / "particles_table.md").string().c_str());
}

}  // namespace

KIRI_BENCH_STAGE({"particles",
                  "Particle light pass: precompute time vs particles (Shimada Table 1)",
                  {"particles", "time_s", "precompute time (s)", true, true},
                  particles_table});

}  // namespace kiri::bench
