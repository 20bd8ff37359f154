#pragma once
// The renderer's origin: where the coordinates it hands the GPU are measured from.
//
// The GPU works in float, whose step is 1 m at 1e7 m: a scene that far from the world's origin
// would lose its fog's edges and its terrain's detail to rounding. The Renderer subtracts this
// origin, in double, from everything it is given (terrain, Medium, layers, particles, overlays,
// the light volume, the camera) before any pass sees it, so every pass and shader works within
// the scene's own extent whatever its world coordinates. A DEM is loaded centred on its data
// (heightfield.hpp), so for every scene kiri builds the origin is (0, 0, 0) and nothing is copied.
#include <memory>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "kiri/geometry/layers/layer_stack.hpp"
#include "kiri/geometry/medium/light_volume.hpp"
#include "kiri/geometry/medium/medium.hpp"
#include "kiri/geometry/particles/particles.hpp"
#include "kiri/geometry/terrain/terrain.hpp"
#include "kiri/geometry/volume/height_fog.hpp"
#include "kiri/render/camera.hpp"
#include "kiri/render/overlay_mesh.hpp"

namespace kiri::render::detail {

//! Within this distance of the world's origin floats keep centimetres (2^16 m: a 4 mm step), and
//! the origin stays (0, 0, 0).
constexpr double render_origin_reach = 65536.0;

//! The origin for a scene over `bounds`: (0, 0, 0) when its centre lies within
//! render_origin_reach of the world's, else that centre rounded to whole kilometres (z 0: a
//! terrain's heights are never that far from sea level).
glm::dvec3 render_origin_for(const geometry::Bounds3& bounds);

//! The noise's drift (wind x time, less the Medium's noise_shift) as the shaders subtract it
//! before dividing by the noise's tile: reduced to [0, tile) in double, since the noise repeats
//! every tile, so that a float keeps it exactly whatever the time or the origin.
glm::dvec2 noise_drift(const glm::dvec2& wind, double time, const glm::dvec2& noise_shift, double tile);

// Each of these returns its argument moved by -origin (the noise of a Medium and of the layers
// stays where it was in the world).
geometry::Heightfield moved(const geometry::Heightfield& heightfield, const glm::dvec3& origin);
geometry::Medium moved(const geometry::Medium& medium, const glm::dvec3& origin);
geometry::HeightFog moved(geometry::HeightFog haze, const glm::dvec3& origin);
geometry::LayerBase moved(const geometry::LayerBase& base, const glm::dvec3& origin);
geometry::ParticleCloud moved(const geometry::ParticleCloud& cloud, const glm::dvec3& origin);
geometry::LightVolume moved(const geometry::LightVolume& volume, const glm::dvec3& origin);
OverlayMesh moved(const OverlayMesh& mesh, const glm::dvec3& origin);
Camera moved(Camera camera, const glm::dvec3& origin);

//! One Medium as a pass sees it: the caller's own (origin 0) or a moved copy, made again only
//! when the caller's Medium changes (a new object, its grids rebuilt, new options or detail),
//! so that the passes' caches keyed on the Medium's identity keep working.
class MovedMedium {
public:
    //! The Medium to hand the passes for `source` (null for null).
    const geometry::Medium* get(const geometry::Medium* source, const glm::dvec3& origin);
    void clear() { *this = {}; }

private:
    const geometry::Medium* source_ = nullptr;
    const void* grids_ = nullptr;
    geometry::MediumOptions options_;
    geometry::MediumDetail detail_;
    glm::dvec3 origin_{0.0};
    std::shared_ptr<const geometry::Medium> copy_;
};

}  // namespace kiri::render::detail
