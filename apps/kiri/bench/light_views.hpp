#pragma once
// The light bench's views (light_bench.cpp): uniform slabs and thin layers generated here, seen
// from above, the side, inside and across at sun elevations of 10, 30 and 60 degrees, and the
// shipped scenes' cameras.
#include <filesystem>
#include <string>
#include <vector>

namespace kiri::bench {

struct LightView {
    std::string name;        //!< file stem of its pictures
    std::string scene;       //!< a generated slab (slab10, thin30, ...) or a stem of data/scenes
    std::string camera;      //!< the scene's camera
    bool fitted_on = false;  //!< one of the views the constants were fitted to
};

//! Every view, or with `quick` the shipped scenes' first cameras only.
std::vector<LightView> light_views(bool quick);

//! The slab scene `name` (slab30, thin10, ...) written into dir (with its flat DEM): a flat 10 km
//! terrain at z = 0 filled with uniform fog (sigma_t 0.02 1/m, albedo 0.99, g 0.8) up to 100 m
//! (slab) or 15 m (thin), the sun at the elevation of the name.
std::filesystem::path write_slab_scene(const std::filesystem::path& dir, const std::string& name);

}  // namespace kiri::bench
