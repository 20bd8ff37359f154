#pragma once
//! \file layer_texture.hpp
//! The layers' texture ([Thesis] 2.2.2): gray, its alpha falling to zero towards the outer
//! border of the footprint and uniform across edges shared between patches. Each patch keeps
//! its full (u, v) mapping; which of its sides and corners lie on the border (its "border
//! mask") picks a tile of a procedurally generated atlas, one tile per mask in use.
#include <cstdint>
#include <map>
#include <vector>

#include <glm/vec2.hpp>

#include "kiri/geometry/core/fields.hpp"
#include "kiri/geometry/fog/footprint.hpp"

namespace kiri::geometry {

struct LayerTextureOptions {
    int resolution = 64;
    double fade_width = 0.5;
    double gray = 0.92;
    bool operator==(const LayerTextureOptions&) const = default;
};

//! Keys of the scene's "layers" section (the texture has no section of its own).
template <fields_of<LayerTextureOptions> O, class V>
void visit_fields(O& o, V&& v)
{
    v(o.resolution,
      {.key = "texture_size", .unit = "texels", .range = closed(4, 1024), .doc = "per side of an atlas tile"});
    v(o.fade_width,
      {.key = "fade_width",
       .range = left_open(0, 1),
       .doc = "share of a patch over which alpha falls to 0 at the border",
       .widget = closed(0.02, 1)});
    v(o.gray, {.key = "gray", .range = closed(0, 1), .doc = "`source` shading: the texture's gray"});
}

//! Bits 0..3: the patch's sides v = 0, u = 1, v = 1, u = 0 lie on the footprint's border.
//! Bits 4..7: its corners (0,0), (1,0), (1,1), (0,1) lie on the border while neither side
//! meeting there does (a concave corner of the footprint), so the fade meets the neighbours'.
using BorderMask = std::uint8_t;
BorderMask patch_border_mask(const ControlMesh& control, int face);

//! Alpha of a patch at (u, v) in [0,1]^2: the product over its border sides of s(d / w) and
//! over its border corners of s(|(u,v) - corner| / w), s the C1 smoothstep, d the distance to
//! the side in parameter units, w the fade width. Equal along shared sides (both patches see
//! the same border sides and corners meeting that side).
double border_alpha(BorderMask mask, double u, double v, double fade_width);

struct LayerTexture {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;          //!< rows from v = 0 up; 8-bit RGBA, not premultiplied
    std::map<BorderMask, glm::ivec2> tiles;  //!< texel origin of each mask's tile
    int resolution = 0;
    //! Atlas coordinates in [0,1]^2 of (u, v) on a patch with this mask: texel centres of the
    //! tile's first and last rows and columns map to u, v = 0 and 1, so bilinear filtering
    //! never reads a neighbouring tile.
    glm::dvec2 atlas_uv(BorderMask mask, double u, double v) const;
};
//! The atlas of the given masks (each once). \throw InputError on options out of range.
LayerTexture make_layer_texture(const std::vector<BorderMask>& masks, const LayerTextureOptions& options);

}  // namespace kiri::geometry
