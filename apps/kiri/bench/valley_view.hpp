#pragma once
// The frame stage's held-out view, shared by the stages that time frames.
#include "kiri/geometry/scene/scene.hpp"

namespace kiri::bench {

//! A view no scene file was tuned for: the eye a third of the way up the fog over the lowest
//! ground of the terrain's middle, looking 3 km along the azimuth whose ground stays lowest.
geometry::CameraSpec valley_camera(const geometry::Scene& scene);

}  // namespace kiri::bench
