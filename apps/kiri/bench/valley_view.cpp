#include "bench/valley_view.hpp"

#include <algorithm>
#include <cmath>

#include "kiri/geometry/medium/medium.hpp"
#include "kiri/geometry/scene/pipeline.hpp"
#include "kiri/geometry/terrain/terrain.hpp"

namespace kiri::bench {

geometry::CameraSpec valley_camera(const geometry::Scene& scene)
{
    geometry::Pipeline pipeline;
    const geometry::PipelineProducts& p = pipeline.run(scene, {geometry::Stage::medium});
    const geometry::Terrain& terrain = *p.terrain;
    const geometry::Medium& medium = *p.medium;
    const geometry::Bounds3 b = terrain.bounds();
    const glm::dvec3 centre = 0.5 * (b.min + b.max), half = 0.35 * (b.max - b.min);
    glm::dvec2 eye(centre);
    double lowest = HUGE_VAL;
    for (int j = 0; j <= 64; ++j)
        for (int i = 0; i <= 64; ++i) {
            const glm::dvec2 q(centre.x + half.x * (i / 32.0 - 1.0), centre.y + half.y * (j / 32.0 - 1.0));
            const geometry::MediumColumn c = medium.column(q.x, q.y);
            const double ground = terrain.height(q.x, q.y);
            if (c.coverage > 0.9 && c.top - ground > 20.0 && ground < lowest) {
                lowest = ground;
                eye = q;
            }
        }
    double best = HUGE_VAL, azimuth = 0.0;
    for (int k = 0; k < 32; ++k) {
        const double a = 2.0 * M_PI * k / 32.0;
        double sum = 0.0;
        for (int s = 1; s <= 8; ++s) {
            const glm::dvec2 q = eye + 400.0 * s * glm::dvec2(std::cos(a), std::sin(a));
            sum += terrain.height(std::clamp(q.x, b.min.x, b.max.x), std::clamp(q.y, b.min.y, b.max.y));
        }
        if (sum < best) {
            best = sum;
            azimuth = a;
        }
    }
    const geometry::MediumColumn c = medium.column(eye.x, eye.y);
    const double ground = terrain.height(eye.x, eye.y);
    geometry::CameraSpec camera;
    camera.name = "valley";
    camera.position = {eye.x, eye.y, ground + std::max(5.0, (c.top - ground) / 3.0)};
    const glm::dvec2 ahead = eye + 3000.0 * glm::dvec2(std::cos(azimuth), std::sin(azimuth));
    camera.target = {ahead.x, ahead.y, camera.position.z - 60.0};
    camera.fov_y_deg = 60.0;
    return camera;
}

}  // namespace kiri::bench
