#include "kiri/geometry/reference/reference_fog.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "reference/fog_marcher.hpp"
#include "core/parallel_rows.hpp"

namespace kiri::geometry {

glm::dvec3 ReferenceView::forward() const
{
    const glm::dvec3 f = target - eye;
    const double len = glm::length(f);
    return len > 0.0 ? f / len : glm::dvec3(0.0, 1.0, 0.0);
}

glm::dvec3 ReferenceView::ray(int x, int y) const { return ray_through(x + 0.5, y + 0.5); }

glm::dvec3 ReferenceView::ray_through(double x, double y) const
{
    // glm::lookAt's frame and glm::perspective's pixel mapping (render::Camera).
    const glm::dvec3 f = forward();
    glm::dvec3 r = glm::cross(f, up);
    r = glm::length(r) > 0.0 ? glm::normalize(r) : glm::dvec3(1.0, 0.0, 0.0);
    const glm::dvec3 u = glm::cross(r, f);
    const double tan_half = std::tan(0.5 * fov_y_deg * 3.14159265358979323846 / 180.0);
    const double aspect = double(width) / double(std::max(height, 1));
    const double nx = x / width * 2.0 - 1.0, ny = 1.0 - y / height * 2.0;
    return glm::normalize(f + r * (nx * tan_half * aspect) + u * (ny * tan_half));
}

double luminance(const glm::dvec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

RayFog reference_ray(const FogVolume& fog, const Heightfield* terrain, const glm::dvec3& origin, const glm::dvec3& dir,
                     double t_max, const FogLighting& light, const ReferenceOptions& options)
{
    const detail::FogMarcher marcher(fog, terrain, light, options);
    detail::MarchScratch scratch;
    return marcher.trace(origin, dir, t_max, scratch);
}

namespace {

// An image of width x height pixels, pixel i of it the ray ray_at(i) from the view's eye; the
// pixels split among the threads in runs of `run`.
template <class RayAt>
ReferenceImage trace_rays(const FogVolume& fog, const Heightfield* terrain, const ReferenceView& view,
                          const FogLighting& light, const ReferenceOptions& options, int width, int height,
                          std::size_t run, RayAt ray_at)
{
    const auto start = std::chrono::steady_clock::now();
    ReferenceImage out;
    out.width = std::max(width, 0);
    out.height = std::max(height, 0);
    const std::size_t n = std::size_t(out.width) * out.height;
    out.inscatter.assign(n, glm::dvec3(0.0));
    out.transmittance.assign(n, 1.0);
    out.background.assign(n, glm::dvec3(0.0));
    out.fog_shade.assign(n, glm::dvec3(0.0));
    out.ground_sun.assign(n, 1.0);
    out.depth.assign(n, std::numeric_limits<double>::infinity());
    const detail::FogMarcher marcher(fog, terrain, light, options);
    const glm::dvec3 forward = view.forward();
    run = std::max<std::size_t>(run, 1);
    const int runs = int((n + run - 1) / run);
    std::atomic<long long> steps{0}, knots{0};
    detail::for_rows_in_parallel(options.threads, runs, [&](auto next_run) {
        detail::MarchScratch scratch;
        long long my_steps = 0, my_knots = 0;
        for (int r = next_run(); r < runs; r = next_run())
            for (std::size_t k = std::size_t(r) * run; k < std::min(n, std::size_t(r + 1) * run); ++k) {
                const glm::dvec3 w = ray_at(k);
                const double cos_axis = glm::dot(w, forward);
                const double t_max = view.max_depth > 0.0 && cos_axis > 0.0 ? view.max_depth / cos_axis : 1e6;
                const RayFog ray = marcher.trace(view.eye, w, t_max, scratch);
                out.inscatter[k] = ray.inscatter;
                out.transmittance[k] = ray.transmittance;
                out.background[k] = ray.surface;
                out.fog_shade[k] = ray.fog_shade;
                out.ground_sun[k] = ray.ground_sun;
                if (ray.hit_terrain)
                    out.depth[k] = ray.distance * cos_axis;
                my_steps += ray.steps;
                my_knots += ray.sun_knots;
            }
        steps += my_steps;
        knots += my_knots;
    });
    out.steps = steps;
    out.sun_knots = knots;
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

}  // namespace

ReferenceImage render_reference_fog(const FogVolume& fog, const Heightfield* terrain, const ReferenceView& view,
                                    const FogLighting& light, const ReferenceOptions& options)
{
    const std::size_t width = std::size_t(std::max(view.width, 1));
    return trace_rays(fog, terrain, view, light, options, view.width, view.height, width,
                      [&](std::size_t k) { return view.ray(int(k % width), int(k / width)); });
}

ReferenceImage render_reference_rays(const FogVolume& fog, const Heightfield* terrain, const ReferenceView& view,
                                     const FogLighting& light, const std::vector<glm::dvec2>& points,
                                     const ReferenceOptions& options)
{
    return trace_rays(fog, terrain, view, light, options, int(points.size()), points.empty() ? 0 : 1, 64,
                      [&](std::size_t k) { return view.ray_through(points[k].x, points[k].y); });
}

}  // namespace kiri::geometry
