#pragma once
// The layer stack the layer tests share: the source's 15 layers over 150 m (Fig. 2.7).
#include "kiri/geometry/layers/layer_stack.hpp"

namespace kiri::test {

inline geometry::LayerOptions options_15()
{
    geometry::LayerOptions o;
    o.count = 15;
    o.thickness = 150.0;  // r0 = 10 m, reference distance L0 = 2000 m
    o.max_count = 120;
    return o;
}

}  // namespace kiri::test
