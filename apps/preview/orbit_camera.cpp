#include "orbit_camera.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace kiri::preview {
namespace {
// Not quite vertical: the view's up vector (z) must stay off the line of sight.
constexpr double max_pitch = 1.55;
constexpr double radians_per_pixel = 0.005;
}  // namespace

void OrbitCamera::look(const glm::dvec3& eye, const glm::dvec3& target, double fov_deg)
{
    target_ = target;
    const glm::dvec3 d = eye - target;
    distance_ = std::max(glm::length(d), 1.0);
    yaw_ = std::atan2(d.y, d.x);
    pitch_ = std::clamp(std::asin(std::clamp(d.z / distance_, -1.0, 1.0)), -max_pitch, max_pitch);
    fov_deg_ = fov_deg;
}

glm::dvec3 OrbitCamera::forward() const
{
    return -glm::dvec3(std::cos(pitch_) * std::cos(yaw_), std::cos(pitch_) * std::sin(yaw_), std::sin(pitch_));
}

glm::dvec3 OrbitCamera::eye() const { return target_ - distance_ * forward(); }

void OrbitCamera::orbit(double dx, double dy)
{
    yaw_ -= dx * radians_per_pixel;
    pitch_ = std::clamp(pitch_ + dy * radians_per_pixel, -max_pitch, max_pitch);
}

void OrbitCamera::look_around(double dx, double dy)
{
    const glm::dvec3 e = eye();
    yaw_ -= dx * radians_per_pixel;
    pitch_ = std::clamp(pitch_ + dy * radians_per_pixel, -max_pitch, max_pitch);
    target_ = e + distance_ * forward();
}

void OrbitCamera::pan(double dx, double dy, double viewport_height)
{
    const glm::dvec3 f = forward();
    const glm::dvec3 right = glm::normalize(glm::cross(f, glm::dvec3(0, 0, 1)));
    const glm::dvec3 up = glm::cross(right, f);
    const double metres_per_pixel =
        2.0 * distance_ * std::tan(fov_deg_ * M_PI / 360.0) / std::max(viewport_height, 1.0);
    target_ += (-dx * right + dy * up) * metres_per_pixel;
}

void OrbitCamera::zoom(double steps) { distance_ = std::clamp(distance_ * std::pow(0.85, steps), 2.0, 2e6); }

void OrbitCamera::fly(double forward_amount, double right_amount, double up_amount, double seconds, double speed)
{
    const glm::dvec3 f = forward();
    const glm::dvec3 r = glm::normalize(glm::cross(f, glm::dvec3(0, 0, 1)));
    target_ += speed * seconds * (forward_amount * f + right_amount * r + up_amount * glm::dvec3(0, 0, 1));
}

void OrbitCamera::set_target(const glm::dvec3& target) { look(eye(), target, fov_deg_); }

render::Camera OrbitCamera::camera() const
{
    render::Camera c;
    c.position = eye();
    c.target = target_;
    c.fov_y_deg = fov_deg_;
    return c;
}

}  // namespace kiri::preview
