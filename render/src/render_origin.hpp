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
#include <tuple>

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

geometry::Terrain moved(const geometry::Terrain& terrain, const glm::dvec3& origin);

//! One object as the passes see it: the caller's own (origin 0) or a copy moved by -origin,
//! made again only when the caller's object changes (`key`: what tells its content apart, e.g.
//! its address and its storage's) or the origin does, so that the passes' caches keyed on the
//! object's identity keep working.
template <class T, class Key>
class MovedCopy {
public:
    //! The object to hand the passes for `source` (null for null).
    const T* get(const T* source, const Key& key, const glm::dvec3& origin)
    {
        if (!source || origin == glm::dvec3(0.0)) {
            clear();
            return source;
        }
        if (!copy_ || !(key == key_) || origin != origin_) {
            copy_ = std::make_shared<const T>(moved(*source, origin));
            key_ = key;
            origin_ = origin;
        }
        return copy_.get();
    }
    //! The copy get() returned last, shared (null when it returned the caller's own).
    const std::shared_ptr<const T>& copy() const { return copy_; }
    void clear() { *this = {}; }

private:
    Key key_{};
    glm::dvec3 origin_{0.0};
    std::shared_ptr<const T> copy_;
};

//! What tells a Medium's content apart: the object, its grids' storage (a Medium rebuilt in
//! place is a new one), its options and its detail (its time among them).
using MediumKey = std::tuple<const geometry::Medium*, const void*, geometry::MediumOptions, geometry::MediumDetail>;
inline MediumKey medium_key(const geometry::Medium* m)
{
    return m ? MediumKey{m, m->grid().top.data(), m->options(), m->detail()} : MediumKey{};
}
using MovedMedium = MovedCopy<geometry::Medium, MediumKey>;

}  // namespace kiri::render::detail
