#include "kiri/render/camera.hpp"

#include <glm/gtc/matrix_transform.hpp>

namespace kiri::render {

glm::dmat4 Camera::view() const { return glm::lookAt(position, target, up); }

glm::dmat4 Camera::projection(double aspect) const
{
    return glm::perspective(glm::radians(fov_y_deg), aspect, near_m, far_m);
}

glm::dvec2 project_to_pixel(const Camera& camera, const glm::dvec3& world, int width, int height)
{
    const glm::dvec4 clip = camera.projection(double(width) / double(height)) * camera.view() * glm::dvec4(world, 1.0);
    const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
    // NDC y points up, image rows go down.
    return {(ndc.x * 0.5 + 0.5) * width, (0.5 - ndc.y * 0.5) * height};
}

}  // namespace kiri::render
