#pragma once
//! \file scene_fog.hpp
//! A scene's fog, ready for the renderers and exporters: the fitted base surface (issue 4) and
//! the layer stack's base and options in world units (issue 5), and the medium they describe.
#include "kiri/geometry/fog_spec.hpp"
#include "kiri/geometry/layer_stack.hpp"
#include "kiri/geometry/medium.hpp"
#include "kiri/geometry/scene.hpp"

namespace kiri::geometry {

struct SceneFog {
    AuthoredSurface authored;
    LayerOptions layers;  //!< world units (world_layer_options)
    LayerBase base;
    Medium medium;  //!< the same fog as a participating medium (medium.hpp), for every volume renderer
    double seconds_layer_base = 0.0, seconds_medium = 0.0;
};

//! Fits and tessellates the scene's fog over `terrain` (loaded with load_scene_terrain) and
//! prepares its layers. \throw InputError naming the scene file (no fog section, bad options).
SceneFog author_scene_fog(const Scene& scene, const Terrain& terrain);

}  // namespace kiri::geometry
