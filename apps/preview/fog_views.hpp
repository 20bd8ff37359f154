#pragma once
// What the preview shows of the fog besides its layers, built on the worker thread from the
// fitted surface: the surface itself (tessellation), its patch borders and control mesh as
// lines, and two colour maps over the surface (the fit's deviation from its target, and the
// height above the terrain).
#include <cstddef>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "kiri/geometry/fog/base_surface.hpp"
#include "kiri/geometry/placement/fog_placement.hpp"
#include "kiri/geometry/layers/layer_stack.hpp"
#include "kiri/geometry/fog/tessellate.hpp"
#include "kiri/render/overlay_mesh.hpp"

namespace kiri::preview {

struct FogViews {
    render::OverlayMesh surface;              //!< the tessellation, lit, white
    std::vector<glm::vec4> deviation_colors;  //!< per surface vertex: blue below target, red above
    std::vector<glm::vec4> clearance_colors;  //!< per surface vertex: height above the terrain
    double deviation_range = 0.0;             //!< metres at full blue / red (98th percentile of |deviation|)
    double clearance_range = 0.0;             //!< metres at the top of the clearance map
    render::OverlayMesh patch_borders;        //!< lines along every patch side, on the surface
    render::OverlayMesh control_mesh;         //!< lines of the fitted control mesh
};

//! fit: the world-unit options the surface was fitted with (the deviation's target).
std::shared_ptr<const FogViews> make_fog_views(const geometry::BaseSurface& surface,
                                               const geometry::Tessellation& tessellation,
                                               const geometry::Terrain& terrain, const geometry::FitOptions& fit);

//! Colour maps: t in [-1, 1] blue - white - red; t in [0, 1] dark violet - teal - yellow.
glm::vec4 diverging_color(double t);
glm::vec4 sequential_color(double t);

}  // namespace kiri::preview
