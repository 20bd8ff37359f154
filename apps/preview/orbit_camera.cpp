#include "orbit_camera.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace kiri::preview {

void OrbitCamera::look(const glm::dvec3& eye, const glm::dvec3& target, double fov_deg)
{
    target_ = target;
    const glm::dvec3 d = eye - target;
    distance_ = std::max(glm::length(d), 1.0);
    yaw_ = std::atan2(d.y, d.x);
    pitch_ = std::asin(std::clamp(d.z / distance_, -1.0, 1.0));
    fov_deg_ = fov_deg;
}

glm::dvec3 OrbitCamera::eye() const
{
    return target_ + distance_ * glm::dvec3(std::cos(pitch_) * std::cos(yaw_), std::cos(pitch_) * std::sin(yaw_),
                                            std::sin(pitch_));
}

void OrbitCamera::orbit(double dx, double dy)
{
    yaw_ -= dx * 0.005;
    // Not quite vertical: the view's up vector (z) must stay off the line of sight.
    pitch_ = std::clamp(pitch_ + dy * 0.005, -1.55, 1.55);
}

void OrbitCamera::pan(double dx, double dy, int viewport_height)
{
    const render::Camera c = camera();
    const glm::dvec3 forward = glm::normalize(c.target - c.position);
    const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(0, 0, 1)));
    const glm::dvec3 up = glm::cross(right, forward);
    const double metres_per_pixel =
        2.0 * distance_ * std::tan(fov_deg_ * M_PI / 360.0) / std::max(viewport_height, 1);
    target_ += (-dx * right + dy * up) * metres_per_pixel;
}

void OrbitCamera::zoom(double steps) { distance_ = std::clamp(distance_ * std::pow(0.85, steps), 5.0, 2e6); }

void OrbitCamera::fly(double forward, double right, double up, double seconds)
{
    const render::Camera c = camera();
    const glm::dvec3 f = glm::normalize(c.target - c.position);
    const glm::dvec3 r = glm::normalize(glm::cross(f, glm::dvec3(0, 0, 1)));
    const double speed = 0.5 * distance_ * seconds;  // crosses half the view distance per second
    target_ += speed * (forward * f + right * r + up * glm::dvec3(0, 0, 1));
}

render::Camera OrbitCamera::camera() const
{
    render::Camera c;
    c.position = eye();
    c.target = target_;
    c.fov_y_deg = fov_deg_;
    return c;
}

}  // namespace kiri::preview
