#pragma once
// The preview's camera: a target, a distance and two angles. Orbit turns the eye about the
// target, look_around turns the view about the eye (fly mode), pan and fly move eye and target
// together (nothing stops the eye from entering the fog or the ground). Angles in radians,
// metres; mouse movements in window pixels.
#include <glm/vec3.hpp>

#include "kiri/render/camera.hpp"

namespace kiri::preview {

class OrbitCamera {
public:
    void look(const glm::dvec3& eye, const glm::dvec3& target, double fov_deg);
    void orbit(double dx_pixels, double dy_pixels);
    void look_around(double dx_pixels, double dy_pixels);
    //! The point under the cursor stays under it: metres per pixel at the target's distance.
    void pan(double dx_pixels, double dy_pixels, double viewport_height_pixels);
    //! Towards the target (positive steps) or away; never through it.
    void zoom(double wheel_steps);
    //! forward/right/up in [-1, 1] for `seconds` at `speed` m/s.
    void fly(double forward, double right, double up, double seconds, double speed);
    //! A new orbit centre, keeping the eye where it is.
    void set_target(const glm::dvec3& target);
    render::Camera camera() const;
    glm::dvec3 eye() const;
    const glm::dvec3& target() const { return target_; }
    double distance() const { return distance_; }

private:
    glm::dvec3 target_{0.0};
    double distance_ = 10000.0, yaw_ = 0.0, pitch_ = 0.5, fov_deg_ = 45.0;
    glm::dvec3 forward() const;  // unit, eye -> target
};

}  // namespace kiri::preview
