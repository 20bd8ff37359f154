#pragma once
// The 2D maps `kiri author` writes for fog placed by the terrain (docs/placement.md).
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "kiri/geometry/scene/scene.hpp"
#include "kiri/geometry/placement/fog_placement.hpp"
#include "kiri/geometry/terrain/terrain.hpp"

namespace kiri::cli {

struct MapFile {
    std::string name;                                         //!< file name in the output folder
    std::function<void(const std::filesystem::path&)> write;  //!< writes it at the given (temporary) path
};

//! fog_top.tif, fog_bottom.tif, fog_thickness.tif (GeoTIFF, DEM metres, the DEM's
//! georeferencing, the optics in their metadata), fog_mask.png, and flood_level.tif for seed
//! points or valleys.png + valley_index.tif for automatic seeding; none without a placement.
std::vector<MapFile> placement_maps(const geometry::Scene& scene, const geometry::Terrain& terrain,
                                    const geometry::PlacedFog* placed);

}  // namespace kiri::cli
