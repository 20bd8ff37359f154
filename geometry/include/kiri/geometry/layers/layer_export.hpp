#pragma once
//! \file layer_export.hpp
//! The layer stack (and the terrain) for other tools: glTF 2.0 binary (.glb), OBJ and PLY.
//! Files are written whole to the given path (callers write to a temporary name and rename).
#include <filesystem>
#include <vector>

#include "kiri/geometry/layers/layer_stack.hpp"
#include "kiri/geometry/terrain/mesh.hpp"

namespace kiri::geometry {

//! .glb, compact: the base's POSITION, NORMAL, TEXCOORD_0 (into the atlas) and triangles once,
//! with one morph target (a layer vertex is p + i d(p): the spacing and the enlargement are
//! linear in the layer index i); one mesh per layer sharing them, with its own COLOR_0 (alpha:
//! the layer's alpha at full texture alpha, 16-bit) and the morph weight i / top on its node.
//! One material with alphaMode BLEND and the atlas as baseColorTexture (PNG); the terrain, when
//! given, as an opaque mesh. kiri's z-up metres sit under a root node rotated to glTF's y-up.
//! \throw IoError.
void write_layers_glb(const std::filesystem::path& path, const LayerBase& base, const std::vector<LayerMesh>& layers,
                      const LayerOptions& options, const TriMesh* terrain = nullptr);
//! OBJ: one group per layer (v, vt into the atlas, vn); the alpha goes in a comment per group.
void write_layers_obj(const std::filesystem::path& path, const LayerBase& base, const std::vector<LayerMesh>& layers);
//! Binary PLY: vertices with x y z, nx ny nz, u v (atlas), alpha and layer; faces per layer.
void write_layers_ply(const std::filesystem::path& path, const LayerBase& base, const std::vector<LayerMesh>& layers,
                      const LayerOptions& options);
//! The alpha of a layer vertex at full texture alpha, seen from above: 1 - exp(-sigma_t alpha r)
//! for LayerShading::medium, 1 - (1 - alpha opacity)^exponent for LayerShading::source.
double exported_alpha(const LayerVertex& v, const LayerOptions& options);

}  // namespace kiri::geometry
