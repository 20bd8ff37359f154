#pragma once
//! \file overlay_mesh.hpp
//! Helper geometry drawn over a frame: what the preview's views show (the fog's base surface,
//! its control mesh and patch borders, the fit's deviation as colours). Triangles or lines with
//! optional per-vertex normals and colours, blended last (over the fog layers), depth-tested
//! against the terrain and never writing depth. Kept apart from the terrain and fog passes.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace kiri::render {

struct OverlayMesh {
    enum class Primitive { triangles, lines };
    Primitive primitive = Primitive::triangles;
    std::vector<glm::vec3> positions;    //!< world metres (as the terrain: exaggeration applied)
    std::vector<glm::vec3> normals;      //!< one per position (lit), or empty (unlit)
    std::vector<glm::vec4> colors;       //!< one per position (display RGBA), or empty (white)
    std::vector<std::uint32_t> indices;  //!< 3 per triangle or 2 per line
};

struct OverlayStyle {
    glm::vec4 color{1.0f};  //!< multiplies the vertex colours; alpha is the opacity
    bool visible = true;
    bool wireframe = false;  //!< triangles drawn as their edges
    //! Fraction of the way to the eye each vertex is moved: lines lying on a surface drawn as
    //! another overlay (or the terrain) stay in front of it (1e-3 is plenty; 0 = none).
    float lift = 0.0f;
    int order = 0;  //!< overlays draw by increasing order, then by name
};

}  // namespace kiri::render
