#pragma once
// Internal: the terrain's albedo as render/shaders/terrain.frag colours it (by height and
// slope, water at the sea's surface), shared by the reference ray marcher's and the path
// tracer's ground.
#include <algorithm>

#include <glm/vec3.hpp>

#include "kiri/geometry/terrain/ground.hpp"

namespace kiri::geometry::detail {

inline glm::dvec3 mix(const glm::dvec3& a, const glm::dvec3& b, double t) { return a + (b - a) * t; }

inline double smoothstep(double a, double b, double x)
{
    const double t = std::clamp((x - a) / (b - a), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

//! height01: (z - z_min) / (z_max - z_min) of the terrain, clamped to [0, 1]; normal_z: the
//! unit normal's z. Values in [0, 1] per channel: the Lambertian albedo.
inline glm::dvec3 terrain_albedo(double height01, double normal_z)
{
    const glm::dvec3 valley(0.16, 0.26, 0.10), slope(0.30, 0.32, 0.15), upland(0.42, 0.40, 0.28),
        rock(0.40, 0.36, 0.32);
    glm::dvec3 base = height01 < 0.5 ? mix(valley, slope, height01 * 2.0) : mix(slope, upland, height01 * 2.0 - 1.0);
    return mix(base, rock, smoothstep(0.18, 0.55, 1.0 - normal_z));
}

//! The albedo of the ground's point p with unit normal n: water at the sea's surface, else
//! terrain_albedo over the grid's heights (the surround takes the colour of its height).
inline glm::dvec3 ground_albedo(const Ground& ground, const glm::dvec3& p, const glm::dvec3& n)
{
    if (ground.is_water(p.z))
        return {water_albedo[0], water_albedo[1], water_albedo[2]};
    const double height01 =
        std::clamp((p.z - ground.z_min()) / std::max(ground.z_max() - ground.z_min(), 1e-3), 0.0, 1.0);
    return terrain_albedo(height01, n.z);
}

}  // namespace kiri::geometry::detail
