#pragma once
// The preview's camera: orbit about a target (left drag), pan (right drag), zoom (wheel), and
// fly with WASD + Q/E (eye and target move together). Angles in radians, metres.
#include <glm/vec3.hpp>

#include "kiri/render/camera.hpp"

namespace kiri::preview {

class OrbitCamera {
public:
    void look(const glm::dvec3& eye, const glm::dvec3& target, double fov_deg);
    void orbit(double dx_pixels, double dy_pixels);
    void pan(double dx_pixels, double dy_pixels, int viewport_height);
    void zoom(double wheel_steps);
    //! forward/right/up in [-1, 1] for `seconds` at a speed proportional to the distance.
    void fly(double forward, double right, double up, double seconds);
    render::Camera camera() const;
    const glm::dvec3& target() const { return target_; }

private:
    glm::dvec3 target_{0.0};
    double distance_ = 10000.0, yaw_ = 0.0, pitch_ = 0.5, fov_deg_ = 45.0;
    glm::dvec3 eye() const;
};

}  // namespace kiri::preview
