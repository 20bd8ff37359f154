#pragma once
//! \file layer_medium.hpp
//! The Medium (medium.hpp) of the authored fog: the layer stack's base filled to the stack's
//! thickness, so the volume renderers draw the fog the layers draw.
#include <string>

#include "kiri/geometry/layers/layer_stack.hpp"
#include "kiri/geometry/medium/medium.hpp"
#include "kiri/geometry/terrain/terrain.hpp"

namespace kiri::geometry {

//! The layer base (make_layer_base) rasterised onto a grid over its bounds; bottom = base z +
//! layers.base_offset, top = bottom + layers.thickness, coverage = the base's atlas alpha (the
//! layers' border fade). The density moves with `options` (detail, wind, time, dissipation),
//! its noise shifted per layer of the stack's layers.count. The enlargement (2.10) is
//! view-dependent and left out. \throw InputError (label names the scene) on bad options.
Medium make_medium(const LayerBase& base, const LayerOptions& layers, const Terrain& terrain,
                   const MediumOptions& options, const std::string& label = {});

}  // namespace kiri::geometry
