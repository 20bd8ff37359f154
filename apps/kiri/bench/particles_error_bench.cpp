// The attenuation buffer's accuracy against its cost: resolution against per-particle error and
// build time (R16F and R32F) at 60,134 particles; the error against the optical depth of a voxel
// along the light (the extinction swept at 128^3); and the default scene's flat fog, where a low
// sun crosses a thin sheet.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "bench/bench.hpp"
#include "bench/particles_scene.hpp"
#include "bench/report.hpp"
#include "kiri/geometry/particles/harris_reference.hpp"
#include "kiri/geometry/particles/particle_footprint.hpp"
#include "kiri/geometry/scene/pipeline.hpp"
#include "kiri/geometry/terrain/terrain.hpp"

namespace kiri::bench {
namespace {

// Effective extinction of the particles along the light (1/m): extinction cross-sections per
// volume times (1 - a c), the part of the removed light that does not stay in the beam.
double beam_extinction(const geometry::ParticleCloud& c)
{
    double carried = 0.0, scatter = 0.0;
    for (const geometry::Particle& p : c.particles) {
        const double x = p.optical_depth * geometry::footprint_area() * p.radius * p.radius;
        carried += x;
        scatter += x * p.albedo * c.forward_scattering;
    }
    return (carried - scatter) / c.density_integral;  // per unit density (the medium's sigma scale)
}

void curves(Context& c)
{
    ParticleBenchScene s(c.data_dir());
    const int repeats = c.quick() ? 2 : 5;
    const std::size_t n = c.quick() ? shimada_counts[0] : shimada_counts[2];
    std::vector<Row> by_time;  // the same rows against time, for the second plot
    {
        const geometry::ParticleCloud cloud = ParticleBenchScene::sample(ParticleBenchScene::cumulus(), n);
        const std::vector<double> exact = geometry::harris_light_pass(cloud, s.sun);
        render::AttenuationBuffer b;
        b.set_particles(cloud);
        for (bool half : {true, false})
            for (int res : {48, 64, 96, 128, 192, 256, 320, 384}) {
                if (c.quick() && res > 256)
                    continue;
                render::AttenuationOptions o;
                o.resolution = res;
                o.half_float = half;
                const BufferBuild r = time_buffer(b, s.sun, o, repeats, exact);
                const std::string series =
                    std::string(half ? "R16F" : "R32F") + ", " + std::to_string(n) + " particles";
                const std::string params = "res=" + std::to_string(res) + " max=" + std::to_string(r.error.max) +
                    " mib=" + std::to_string(r.bytes / 1048576.0);
                c.add({series, params, double(res), r.best_s, "mean relative error of Gamma", r.error.mean,
                       double(n) / r.best_s, 0.0});
                by_time.push_back({series, params, r.best_s, r.best_s, "", r.error.mean, 0.0, 0.0});
            }
    }
    Stage against_time{"particles_error_time",
                       "Attenuation buffer: per-particle error against build time (points: resolutions)",
                       {"build time (s)", "error_value", "mean relative error of Gamma", true, true},
                       {}};
    write_plot(c.out_dir() / "particles_error_time.png", against_time, by_time);

    // Error against the optical depth of one voxel along the light: the extinction swept at 128^3.
    std::vector<Row> sweep;
    std::ofstream md(c.out_dir() / "particles_error.md");
    md << "Error at 128^3 (R16F) against the cumulus's extinction, " << n << " particles:\n\n"
       << "| extinction (1/m) | visibility (m) | beam optical depth of a voxel | mean log Gamma | mean error | max error |\n"
       << "|---|---|---|---|---|---|\n";
    for (double sigma : {0.001, 0.002, 0.004, 0.008, 0.016, 0.032}) {
        if (c.quick() && sigma > 0.008)
            break;
        const geometry::ParticleCloud cloud = ParticleBenchScene::sample(ParticleBenchScene::cumulus(sigma), n);
        const std::vector<double> exact = geometry::harris_light_pass(cloud, s.sun);
        render::AttenuationBuffer b;
        b.set_particles(cloud);
        render::AttenuationOptions o;
        const BufferBuild r = time_buffer(b, s.sun, o, 1, exact);
        const double per_voxel = beam_extinction(cloud) * b.grid().voxel.z;
        double mean_log = 0.0;
        for (double g : exact)
            mean_log += std::log(g);
        sweep.push_back({"128^3 R16F, " + std::to_string(n) + " particles", "sigma=" + std::to_string(sigma), per_voxel,
                         r.best_s, "", r.error.mean, 0.0, 0.0});
        md << "| " << sigma << " | " << std::lround(3.912 / sigma) << " | " << per_voxel << " | "
           << mean_log / double(n) << " | " << r.error.mean * 100 << " % | " << r.error.max * 100 << " % |\n";
    }
    Stage against_depth{
        "particles_error_depth",
        "Attenuation buffer at 128^3: error against a voxel's optical depth along the light",
        {"optical depth of a voxel along the light (beam)", "error_value", "mean relative error of Gamma", true, true},
        {}};
    write_plot(c.out_dir() / "particles_error_depth.png", against_depth, sweep);

    // The default scene's fog: a 300 m sheet over 30 km under a 19 degree sun.
    {
        const geometry::PipelineProducts fog = geometry::author_scene(s.scene, {geometry::Stage::medium});
        const geometry::ParticleCloud cloud = ParticleBenchScene::sample(*fog.medium, n);
        const std::vector<double> exact = geometry::harris_light_pass(cloud, s.sun);
        render::AttenuationBuffer b;
        b.set_particles(cloud);
        md << "\nThe default scene's fog (" << n << " particles, extinction " << fog.medium->options().extinction
           << " 1/m), R16F:\n\n| resolution | frame | voxel (m) | build (ms) | mean error | max error |\n|---|---|---|---|---|---|\n";
        for (int res : {128, 256, 384}) {
            if (c.quick() && res > 128)
                continue;
            render::AttenuationOptions o;
            o.resolution = res;
            const BufferBuild r = time_buffer(b, s.sun, o, repeats, exact);
            const auto& v = b.grid().voxel;
            md << "| " << res << "^3 | " << (b.grid().frame == geometry::LightFrame::sheared ? "sheared" : "light")
               << " | " << v.x << " x " << v.y << " x " << v.z << " | " << r.best_s * 1e3 << " | " << r.error.mean * 100
               << " % | " << r.error.max * 100 << " % |\n";
            c.add({"Jacksboro fog, R16F", "res=" + std::to_string(res), double(res), r.best_s,
                   "mean relative error of Gamma", r.error.mean, double(n) / r.best_s, 0.0});
        }
    }
    std::printf("  tables: %s, plots: particles_error_time.png, particles_error_depth.png\n",
                (c.out_dir() / "particles_error.md").string().c_str());
}

}  // namespace

KIRI_BENCH_STAGE({"particles_error",
                  "Attenuation buffer: per-particle error against resolution",
                  {"resolution (voxels per side)", "error_value", "mean relative error of Gamma", true, true},
                  curves});

}  // namespace kiri::bench
