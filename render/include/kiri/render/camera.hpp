#pragma once
//! \file camera.hpp
//! Perspective camera in local metres (z up).
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace kiri::render {

struct Camera {
    glm::dvec3 position{0.0, -1000.0, 1000.0};
    glm::dvec3 target{0.0};
    glm::dvec3 up{0.0, 0.0, 1.0};
    double fov_y_deg = 45.0;
    double near_m = 1.0;
    double far_m = 1.0e6;

    glm::dmat4 view() const;
    //! OpenGL clip space (depth -1..1).
    glm::dmat4 projection(double aspect) const;
};

//! Pixel of a world point in an image of width x height; origin at the top-left corner of
//! the top-left pixel, pixel centres at half-integers (as PNG rows are written).
glm::dvec2 project_to_pixel(const Camera& camera, const glm::dvec3& world, int width, int height);

}  // namespace kiri::render
