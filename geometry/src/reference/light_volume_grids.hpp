#pragma once
// The light volume's grids over its cells' rectangle, filled by the bake
// (light_volume_bake.cpp): the cells' floors down to the ground under a height fog, the terrain's
// shadow's tops, and the sunlit and shadowed parts' L_00 of cells too small to measure one.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "kiri/geometry/medium/light_volume.hpp"
#include "kiri/geometry/medium/medium.hpp"
#include "kiri/geometry/terrain/heightfield.hpp"

namespace kiri::geometry::detail {

//! LightVolume::floors where the height fog lies under the Medium's floor (none where it does not).
void lower_floors_to_the_ground(LightVolume& v, const Medium& medium, const Heightfield& hf);

//! LightVolume::shadow_tops for the sun towards `sun` (unit), on the floors' grid.
void mark_the_terrains_shadow(LightVolume& v, const Heightfield& hf, const glm::dvec3& sun, int threads);

//! A cell's sunlit and shadowed parts' L_00 (LightVolume::class_means) are measured where a part
//! holds at least this share of the cell's volume; a smaller part takes its neighbours' mean.
inline constexpr double least_sunlit_part = 0.15, least_shadowed_part = 0.02;

//! Fills the parts too small to measure (`known` 0) with the mean of their known neighbours' (the
//! 26 around, repeated outwards), else the cell's own L_00.
void fill_unknown_parts(LightVolume& v, std::vector<std::uint8_t>& known);

}  // namespace kiri::geometry::detail
