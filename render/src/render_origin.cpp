#include "render_origin.hpp"

#include <cmath>

namespace kiri::render::detail {

glm::dvec3 render_origin_for(const geometry::Bounds3& bounds)
{
    const glm::dvec2 centre = 0.5 * (glm::dvec2(bounds.min) + glm::dvec2(bounds.max));
    if (!std::isfinite(centre.x) || !std::isfinite(centre.y) ||
        (std::abs(centre.x) <= render_origin_reach && std::abs(centre.y) <= render_origin_reach))
        return glm::dvec3(0.0);
    return {1000.0 * std::round(centre.x / 1000.0), 1000.0 * std::round(centre.y / 1000.0), 0.0};
}

glm::dvec2 noise_drift(const glm::dvec2& wind, double time, const glm::dvec2& noise_shift, double tile)
{
    glm::dvec2 d = wind * time - noise_shift;
    if (!(tile > 0.0) || !std::isfinite(d.x) || !std::isfinite(d.y))
        return glm::dvec2(0.0);
    d -= tile * glm::floor(d / tile);
    return d;
}

geometry::Heightfield moved(const geometry::Heightfield& heightfield, const glm::dvec3& origin)
{
    geometry::Heightfield h = heightfield;
    h.x0 -= origin.x;
    h.y0 -= origin.y;
    for (double& z : h.z)
        z -= origin.z;
    return h;
}

geometry::Terrain moved(const geometry::Terrain& terrain, const glm::dvec3& origin)
{
    return geometry::Terrain(moved(terrain.heightfield(), origin));
}

geometry::Medium moved(const geometry::Medium& medium, const glm::dvec3& origin)
{
    geometry::MediumGrid grid = medium.grid();
    grid.x0 -= origin.x;
    grid.y0 -= origin.y;
    for (std::vector<double>* level : {&grid.floor, &grid.bottom, &grid.top})
        for (double& z : *level)
            z -= origin.z;
    geometry::MediumDetail detail = medium.detail();
    detail.noise_shift += glm::dvec2(origin);
    return geometry::Medium(std::move(grid), medium.options(), detail);
}

geometry::HeightFog moved(geometry::HeightFog haze, const glm::dvec3& origin)
{
    haze.min -= glm::dvec2(origin);  // infinite extents stay infinite
    haze.max -= glm::dvec2(origin);
    haze.base -= origin.z;
    return haze;
}

geometry::LayerBase moved(const geometry::LayerBase& base, const glm::dvec3& origin)
{
    geometry::LayerBase b = base;
    for (glm::dvec3& p : b.position)
        p -= origin;
    b.centre -= glm::dvec2(origin);
    b.min -= origin;
    b.max -= origin;
    return b;
}

geometry::ParticleCloud moved(const geometry::ParticleCloud& cloud, const glm::dvec3& origin)
{
    geometry::ParticleCloud c = cloud;
    for (geometry::Particle& p : c.particles)
        p.position -= origin;
    return c;
}

geometry::LightVolume moved(const geometry::LightVolume& volume, const glm::dvec3& origin)
{
    geometry::LightVolume v = volume;  // its levels are relative to the shell's columns
    v.x0 -= origin.x;
    v.y0 -= origin.y;
    // The height fog's and the cells' floors are heights.
    v.haze_base -= origin.z;
    v.haze_top -= origin.z;
    for (double& z : v.floors)
        z -= origin.z;
    return v;
}

OverlayMesh moved(const OverlayMesh& mesh, const glm::dvec3& origin)
{
    OverlayMesh m = mesh;
    for (glm::vec3& p : m.positions)
        p = glm::vec3(glm::dvec3(p) - origin);
    return m;
}

Camera moved(Camera camera, const glm::dvec3& origin)
{
    camera.position -= origin;
    camera.target -= origin;
    return camera;
}

}  // namespace kiri::render::detail
