#include "frame_context.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "kiri/geometry/medium/air_light.hpp"

namespace kiri::render::detail {

FrameContext make_frame_context(const Camera& camera, const SunLight& sun, int width, int height,
                                const glm::dvec3& scene_min, const glm::dvec3& scene_max, double terrain_across)
{
    FrameContext f;
    f.width = width;
    f.height = height;
    Camera fitted = camera;
    if (scene_max.x >= scene_min.x) {
        double far_distance = 0.0;
        for (int corner = 0; corner < 8; ++corner) {
            const glm::dvec3 p((corner & 1) ? scene_max.x : scene_min.x, (corner & 2) ? scene_max.y : scene_min.y,
                               (corner & 4) ? scene_max.z : scene_min.z);
            far_distance = std::max(far_distance, glm::length(p - camera.position));
        }
        const glm::dvec3 nearest = glm::clamp(camera.position, scene_min, scene_max);
        const double near_distance = glm::length(nearest - camera.position);
        fitted.far_m = std::max(far_distance * 1.05, 10.0);
        // A 32-bit float depth buffer keeps a far/near ratio of 1e5 comfortably.
        fitted.near_m = std::clamp(near_distance * 0.9, std::max(fitted.far_m * 1e-5, 0.05), fitted.far_m * 0.5);
    }
    // The air: the same for every renderer and the CPU reference (FogLighting::air).
    const geometry::AirLight air = geometry::scene_air(terrain_across, sun.ambient, sun.sky);
    f.haze_density = float(air.extinction);
    f.view = fitted.view();
    f.projection = fitted.projection(double(width) / double(height));
    const glm::dmat4 vp = f.projection * f.view;
    f.view_projection = glm::mat4(vp);
    f.inverse_view_projection = glm::mat4(glm::inverse(vp));
    const glm::dmat4& V = f.view;
    f.ray_forward = glm::dvec3(-V[0][2], -V[1][2], -V[2][2]);
    f.ray_right = glm::dvec3(V[0][0], V[1][0], V[2][0]) / f.projection[0][0];
    f.ray_up = glm::dvec3(V[0][1], V[1][1], V[2][1]) / f.projection[1][1];
    f.eye = glm::vec3(camera.position);
    const double len = glm::length(sun.direction);
    f.sun_direction = glm::vec3(len > 0.0 ? sun.direction / len : glm::dvec3(0.0, 0.0, 1.0));
    f.sun_radiance = glm::vec3(sun.color * sun.intensity);
    f.ambient = glm::vec3(sun.ambient);
    // The sky is the ambient light seen directly: deeper blue overhead, paler at the horizon.
    f.sky_zenith = glm::vec3(sun.ambient * glm::dvec3(0.9, 1.5, 2.6));
    f.sky_horizon = glm::vec3(geometry::sky_horizon(sun.ambient));
    f.ground_albedo = sun.black_ground ? 0.0f : 1.0f;
    if (!sun.sky) {  // a black world: no sky light, no sky, no glow
        f.ambient = f.sky_zenith = f.sky_horizon = glm::vec3(0.0f);
        f.sun_glow = false;
    }
    return f;
}

glm::vec2 depth_planes(const FrameContext& frame)
{
    const double p22 = frame.projection[2][2], p32 = frame.projection[3][2];
    return {float(p32 / (p22 - 1.0)), float(p32 / (p22 + 1.0))};
}

bool box_in_view(const FrameContext& frame, const glm::dvec3& lo, const glm::dvec3& hi)
{
    std::array<glm::dvec4, 8> clip;
    for (int c = 0; c < 8; ++c)
        clip[c] = frame.projection * frame.view *
            glm::dvec4(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z, 1.0);
    for (int axis = 0; axis < 3; ++axis)
        for (double side : {-1.0, 1.0}) {
            bool all_out = true;
            for (const glm::dvec4& q : clip)
                all_out = all_out && side * q[axis] > q.w;
            if (all_out)
                return false;
        }
    return true;
}

}  // namespace kiri::render::detail
