// The sun volume (render/src/sun_volume.hpp): tau_sun as the froxels' and the layers' lighting
// read it, at many points, against the Medium's own extinction integrated along the ray towards
// the sun in double (fine steps): the definition the CPU reference marches. Its rebuilds follow
// the sun, the Medium and its time only.
#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "kiri/geometry/medium/medium.hpp"
#include "kiri/render/renderer.hpp"
#include "render/render_fixture.hpp"
#include "sun_volume.hpp"

namespace {

namespace g = kiri::geometry;
using kiri::render::detail::SunVolume;

constexpr double sigma = 0.01;  // 1/m

// A grid of n x n samples d apart from (x0, x0), the fog from the ground (z = 0) to top(x, y).
template <class Top>
g::Medium shell(int n, double d, double x0, Top top, double detail = 0.0, double top_density = 1.0)
{
    g::MediumGrid grid;
    grid.nx = grid.ny = n;
    grid.dx = grid.dy = d;
    grid.x0 = grid.y0 = x0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            grid.floor.push_back(0.0);
            grid.bottom.push_back(0.0);
            grid.top.push_back(top(x0 + i * d, x0 + j * d));
            grid.coverage.push_back(1.0);
        }
    g::MediumOptions options;
    options.extinction = sigma;
    options.top_density = top_density;
    g::MediumDetail fine;
    fine.detail = detail;
    fine.detail_scale = 200.0;
    return g::Medium(std::move(grid), options, fine);
}

// The Medium's optical depth from p towards s (unit), 0.25 m steps at their middles, until the
// ray is above every top.
double integrated_depth(const g::Medium& medium, const glm::dvec3& p, const glm::dvec3& s)
{
    const double ceiling = medium.bounds().max.z, step = 0.25;
    double tau = 0.0;
    for (double t = 0.5 * step; p.z + t * s.z < ceiling + step; t += step)
        tau += medium.extinction(p + (t * s)) * step;
    return tau;
}

glm::dvec3 sun_at(double elevation_deg, double azimuth_deg)
{
    const double e = glm::radians(elevation_deg), a = glm::radians(azimuth_deg);
    return {std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
}

struct Errors {
    double mean = 0.0, max = 0.0;
};

// The volume's tau_sun at `points` against the integral: relative errors, each over
// max(tau, 1): below 1 the error in tau is about that in the sun's transmittance.
Errors compare(const g::Medium& medium, const glm::dvec3& sun, const std::vector<glm::vec3>& points,
               bool use_volume = true)
{
    SunVolume volume;
    volume.set(&medium, {});
    volume.update(glm::vec3(sun));
    EXPECT_TRUE(volume.ready());
    const std::vector<float> got = volume.probe(points, glm::vec3(sun), 12, use_volume);
    Errors e;
    for (std::size_t k = 0; k < points.size(); ++k) {
        const double want = integrated_depth(medium, glm::dvec3(points[k]), glm::normalize(sun));
        const double error = std::abs(got[k] - want) / std::max(want, 1.0);
        e.mean += error / double(points.size());
        if (error > e.max && std::getenv("KIRI_DEBUG"))
            std::printf("      worst so far at (%.0f %.0f %.1f): %.4f want %.4f\n", points[k].x, points[k].y,
                        points[k].z, got[k], want);
        e.max = std::max(e.max, error);
    }
    return e;
}

class SunVolumeGl : public kiri::test::GlTest {};

}  // namespace

// A uniform slab 100 m thick: tau = sigma (top - z) / sin(elevation) wherever the sun's path
// leaves through the top (away from the grid's edges), in closed form.
TEST_F(SunVolumeGl, UniformSlabIsTheClosedForm)
{
    const g::Medium slab = shell(41, 50.0, -1000.0, [](double, double) { return 100.0; });
    const glm::dvec3 sun = sun_at(30.0, 20.0);
    std::vector<glm::vec3> points;
    for (double x = -600.0; x <= 600.0; x += 97.0)
        for (double y = -600.0; y <= 600.0; y += 131.0)
            for (double z = 0.5; z < 100.0; z += 9.7)
                points.emplace_back(float(x), float(y), float(z));
    SunVolume volume;
    volume.set(&slab, {});
    volume.update(glm::vec3(sun));
    const std::vector<float> got = volume.probe(points, glm::vec3(sun), 12);
    double worst = 0.0;
    for (std::size_t k = 0; k < points.size(); ++k) {
        const double want = sigma * (100.0 - points[k].z) / std::sin(glm::radians(30.0));
        worst = std::max(worst, std::abs(got[k] - want));
    }
    std::printf("    uniform slab: %zu points, largest error in tau %.5f (tau up to 2)\n", points.size(), worst);
    EXPECT_LT(worst, 0.01);
}

// The fog's top steps from 100 m (x < 0) to 300 m (x > 0), the sun low over the high side. Above
// the low side's top the local column holds no fog, yet the sun's slanted path crosses the high
// side's: tau up to 4 there. A volume that took the column above each point would give 0.
TEST_F(SunVolumeGl, SlantedPathAcrossAStepInTheTop)
{
    const g::Medium step = shell(41, 50.0, -1000.0, [](double x, double) { return x < 0.0 ? 100.0 : 300.0; });
    const glm::dvec3 sun = sun_at(30.0, 0.0);
    std::vector<glm::vec3> points;
    for (double x = -450.0; x <= 400.0; x += 37.0)
        for (double y = -300.0; y <= 300.0; y += 150.0)
            for (double z = 2.0; z < 300.0; z += 23.0)
                points.emplace_back(float(x), float(y), float(z));
    const Errors e = compare(step, sun, points);
    std::printf("    step in the top: %zu points, relative error mean %.4f, max %.4f\n", points.size(), e.mean, e.max);
    EXPECT_LT(e.mean, 0.01);
    EXPECT_LT(e.max, 0.15);  // just above the low top, where tau(z) kinks between two levels
}

// A rolling top (60 to 240 m), the density thinning to 0.1 at the top and the detail noise: the
// volume against the integral, and no worse than the froxels' own 12-step march at the points.
TEST_F(SunVolumeGl, RollingTopWithDetailAgreesWithTheIntegral)
{
    const g::Medium fog = shell(
        65, 40.0, -1280.0, [](double x, double y) { return 150.0 + 90.0 * std::sin(x / 230.0) * std::cos(y / 310.0); },
        0.6, 0.1);
    for (double elevation : {15.0, 40.0, 70.0}) {
        const glm::dvec3 sun = sun_at(elevation, 35.0);
        std::vector<glm::vec3> points;
        for (double x = -900.0; x <= 900.0; x += 71.0)
            for (double y = -900.0; y <= 900.0; y += 113.0)
                for (double h = 0.02; h < 1.0; h += 0.16) {
                    const double top = 150.0 + 90.0 * std::sin(x / 230.0) * std::cos(y / 310.0);
                    points.emplace_back(float(x), float(y), float(h * top));
                }
        const Errors volume = compare(fog, sun, points), march = compare(fog, sun, points, false);
        std::printf(
            "    rolling top, sun %.0f deg: relative error mean %.4f max %.4f (the 12-step march: %.4f, %.4f)\n",
            elevation, volume.mean, volume.max, march.mean, march.max);
        EXPECT_LT(volume.mean, 0.01);
        EXPECT_LT(volume.max, 0.15);
        EXPECT_LT(volume.mean, 0.3 * march.mean);
    }
}

// A uniform slab 100 m thick over the whole grid, the sun low behind its west edge: the grid's
// edge is a wall of fog, and the sun's path from a point near it leaves through the wall
// (tau = sigma x its length to the wall) or over it (sigma (top - z) / sin(elevation)). Where the
// path grazes the wall's top, tau kinks between the volume's columns: read there, their linear
// blend took up to sigma h / (4 cos(elevation)) off it (h the columns' spacing).
TEST_F(SunVolumeGl, PathsThatGrazeTheGridsEdgeWallKeepTheirKink)
{
    const g::Medium slab = shell(41, 50.0, -1000.0, [](double, double) { return 100.0; });
    for (double elevation : {10.0, 30.0, 60.0}) {
        const glm::dvec3 sun = sun_at(elevation, 200.0);
        std::vector<glm::vec3> points;
        for (double x = -999.0; x <= -400.0; x += 7.3)
            for (double y = -600.0; y <= 600.0; y += 97.0)
                for (double z = 0.5; z < 100.0; z += 6.1)
                    points.emplace_back(float(x), float(y), float(z));
        const Errors e = compare(slab, sun, points);
        std::printf("    the grid's edge, sun %.0f deg: %zu points, relative error mean %.4f, max %.4f\n", elevation,
                    points.size(), e.mean, e.max);
        EXPECT_LT(e.mean, 0.002);
        EXPECT_LT(e.max, 0.02);
    }
}

// Threads of fog 25 m deep in the floors of valleys 240 m apart, the sun low across them, over a
// grid of 20 m samples 10 km wide, as the fill makes over a DEM (Jacksboro's fog: 230 m a column
// at 128 columns). The fog near each point varies within a column there, and the point's level
// in the shell maps to other heights in the neighbouring columns, on the valley's sides: their
// blend missed the thread's own fog on the sun's side. The columns 54 m apart here (192 a side):
// error in tau 0.054 and 0.024 on average with the sun 15 and 35 degrees up; 80 m apart (128, as
// before): 0.086 and 0.047; 40 m apart (256): 0.036 and 0.011.
TEST_F(SunVolumeGl, ThreadsOfFogInNarrowValleys)
{
    const auto floor = [](double x, double) { return 30.0 * (1.0 - std::cos(2.0 * M_PI * x / 240.0)); };
    g::MediumGrid grid;
    grid.nx = grid.ny = 513;
    grid.dx = grid.dy = 20.0;
    grid.x0 = grid.y0 = -5120.0;
    for (int j = 0; j < grid.ny; ++j)
        for (int i = 0; i < grid.nx; ++i) {
            const double z = floor(grid.x0 + i * grid.dx, grid.y0 + j * grid.dy);
            grid.floor.push_back(z);
            grid.bottom.push_back(z);
            grid.top.push_back(std::max(z, 25.0));
            grid.coverage.push_back(1.0);
        }
    g::MediumOptions options;
    options.extinction = 0.02;
    const g::Medium fog(std::move(grid), options, {});
    for (const auto& [elevation, bound] : {std::pair{15.0, 0.07}, std::pair{35.0, 0.035}}) {
        const glm::dvec3 sun = sun_at(elevation, 10.0);
        std::vector<glm::vec3> points;
        for (double x = -700.0; x <= 700.0; x += 7.1)
            for (double y = -600.0; y <= 600.0; y += 173.0)
                for (double h = 0.05; h < 1.0; h += 0.15) {
                    const double z0 = floor(x, y);
                    if (z0 < 25.0)
                        points.emplace_back(float(x), float(y), float(z0 + h * (25.0 - z0)));
                }
        SunVolume volume;
        volume.set(&fog, {});
        volume.update(glm::vec3(sun));
        const std::vector<float> got = volume.probe(points, glm::vec3(sun), 12);
        double mean = 0.0, worst = 0.0;
        for (std::size_t k = 0; k < points.size(); ++k) {
            const double want = integrated_depth(fog, glm::dvec3(points[k]), glm::normalize(sun));
            const double error = std::abs(got[k] - want);  // tau up to about 2: that in the sun's transmittance
            mean += error / double(points.size());
            worst = std::max(worst, error);
        }
        std::printf("    threads in valleys, sun %.0f deg: %zu points, error in tau mean %.4f, max %.4f\n", elevation,
                    points.size(), mean, worst);
        EXPECT_LT(mean, bound);
        EXPECT_LT(worst, 0.6);
    }
}

// A static view reuses the volume: new cameras do not rebuild it; the sun, the Medium and its
// time do, once each.
TEST_F(SunVolumeGl, RebuiltOnlyWhenTheSunOrTheFogChanges)
{
    const g::Terrain terrain = kiri::test::gaussian_hill();
    g::Medium fog = shell(
        33, 20.0, -320.0, [](double, double) { return 120.0; }, 0.6);
    kiri::render::Renderer renderer;
    renderer.set_terrain(terrain);
    renderer.set_sun_medium(&fog, {});
    kiri::render::Camera camera;
    camera.position = {-900.0, -900.0, 600.0};
    camera.target = {0.0, 0.0, 50.0};
    const auto updates = [&] { return renderer.last_stats().sun_volume_updates; };
    const auto timed = [&] {  // the frame reports the pass only when it ran
        const auto& passes = renderer.last_stats().passes;
        return std::any_of(passes.begin(), passes.end(), [](const auto& p) { return p.pass == "sun volume"; });
    };
    renderer.draw(camera, 64, 36);
    EXPECT_EQ(updates(), 1);
    EXPECT_TRUE(timed());
    renderer.draw(camera, 64, 36);
    EXPECT_FALSE(timed());
    camera.position.x += 300.0;
    renderer.draw(camera, 64, 36);
    EXPECT_EQ(updates(), 1) << "the same sun and fog from another view";
    EXPECT_FALSE(timed());
    kiri::render::SunLight sun;
    sun.direction = {0.2, 0.4, 0.7};
    renderer.set_sun(sun);
    renderer.draw(camera, 64, 36);
    EXPECT_EQ(updates(), 2) << "a new sun";
    renderer.draw(camera, 64, 36);
    EXPECT_EQ(updates(), 2);
    fog.set_time(30.0);
    renderer.draw(camera, 64, 36);
    EXPECT_EQ(updates(), 3) << "the fog moved on in time";
    renderer.draw(camera, 64, 36);
    EXPECT_EQ(updates(), 3);
}
