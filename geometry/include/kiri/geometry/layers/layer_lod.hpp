#pragma once
//! \file layer_lod.hpp
//! A level of detail of the layer base for one view. The layers are drawn as instances of the
//! base's triangles, one per layer, so on a rasteriser bound by triangles (a CPU's) the base's
//! count times the layers' is the pass's cost, while away from the eye a patch covers a few pixels
//! and its 2 N^2 triangles are far smaller than a pixel. Per patch a coarser grid of the same
//! vertices is drawn instead: points of the exact surface, so nothing moves, only the
//! interpolation between them is coarser. Neighbours of different levels meet with the
//! tessellation's own transition strips (tessellate.hpp) on the finer level's edge points, so
//! the mesh stays crack-free.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "kiri/geometry/layers/layer_stack.hpp"

namespace kiri::geometry {

//! The base's vertices per patch (layer_patch_grid.hpp) from its tessellation: empty unless the
//! tessellation is uniform and every patch holds each of its grid's points exactly once.
//! Neighbours are found by their shared corners' positions, which the tessellation copies exactly.
LayerPatchGrid make_layer_patch_grid(const Tessellation& tessellation, const std::vector<glm::dvec3>& position);

//! Per patch, the level (cells per side, a divisor of the base's grid level) whose cells span
//! about `edge_pixels` on screen, from the patch's bounding sphere grown by `stack_height` (the
//! layers stand above the base) seen from `eye`; the full level for a patch the eye is in or
//! near. `pixels_per_radian` = (viewport height / 2) / tan(fov_y / 2). Empty when the base has
//! no patch grid. Non-finite inputs give the full level everywhere.
std::vector<int> layer_lod_levels(const LayerBase& base, const glm::dvec3& eye, double pixels_per_radian,
                                  double edge_pixels, double stack_height);

//! The triangles (3 indices into the base's vertices each, counter-clockwise as the base's) of
//! every patch at its level; each patch side at the larger of its two patches' levels. Levels
//! all equal to the grid's give the base's own triangles (the same set). \throw InputError when
//! the levels do not match the patches or are not divisors of the grid's level.
std::vector<std::uint32_t> layer_lod_triangles(const LayerPatchGrid& grid, const std::vector<int>& levels);

}  // namespace kiri::geometry
