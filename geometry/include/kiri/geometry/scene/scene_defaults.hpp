#pragma once
//! \file scene_defaults.hpp
//! Terrain-derived defaults: every key a scene file leaves out (Scene::given) that depends on
//! the terrain is derived from it, once, where the Pipeline turns the scene into world units,
//! and recorded so that the apps can say what they chose. Keys the file gives are never touched,
//! nor values changed in code since (the preview's panels); a scene built in code (no
//! Scene::given) is taken as it is.
//!
//! The rules, each in the units a user writes (metres of the DEM):
//! - exaggeration: low relief is stretched until it rises 4 % of the extent (at most x 5);
//! - patch size: about 8 cells a patch, coarser when more than `max_patches` would cover the
//!   terrain; with it, the tessellation level: 8, less where the patches would pass
//!   `max_triangles`;
//! - a blanket without offset and thickness: both from the relief;
//! - a fill region without a top: the fog covers 30 % of the land, and is a fifth of the relief
//!   deep at least (on a coast, it lies on the sea rather than on the sea floor);
//! - the medium's visibility, when the scene gives no extinction: the fog's optical depth kept
//!   between 2 and 6 (neither invisible nor an opaque plate), by Koschmieder's law [Koschmieder24];
//! - the sun's direction: from the west-north-west, low enough for the slopes to cast shadows;
//! - cameras: "overview" (oblique, the terrain filling the frame), "valley" (low over the lowest
//!   valley) and "inside" (in the fog of that valley).
#include <string>
#include <vector>

#include "kiri/geometry/scene/scene.hpp"
#include "kiri/geometry/terrain/heightfield.hpp"
#include "kiri/geometry/terrain/terrain.hpp"

namespace kiri::geometry {

//! One derived key.
struct DerivedValue {
    std::string key;     //!< its JSON pointer ("/fog/patch_size")
    std::string value;   //!< as a scene writes it ("2000")
    std::string reason;  //!< why, in a few words ("12 cells of 160 m")
    bool operator==(const DerivedValue&) const = default;
};

struct DerivedDefaults {
    std::vector<DerivedValue> values;
    //! "key value (reason); ..." on one line; empty when nothing was derived.
    std::string summary() const;
    bool operator==(const DerivedDefaults&) const = default;
};

//! The budgets the derived patch size and tessellation keep to.
inline constexpr int max_patches = 2000;
inline constexpr int max_triangles = 250000;

//! What the rules read of a terrain, in metres of the DEM (its heights divided by the
//! exaggeration it was loaded with). Land: the valid cells, above 0 when the DEM is a coast
//! (at least 2 % of its valid cells at or below 0, as SRTM's sea, and 2 % above), so that the
//! sea and its floor count no valleys.
struct TerrainFigures {
    double low = 0.0, fill_level = 0.0, median = 0.0, high = 0.0;  //!< land quantiles 2, 30, 50, 98 %
    double width = 0.0, depth = 0.0;                               //!< extent along x and y (m)
    double cell = 0.0;                                             //!< the larger sample spacing (m)
    double mean_slope = 0.0;                                       //!< mean |grad z| over the land
    bool coast = false;
    glm::dvec2 lowest{0.0};  //!< the lowest land sample away from the edges (local m)
    double relief() const { return high - low; }
};
TerrainFigures terrain_figures(const Heightfield& hf, double exaggeration = 1.0);

//! The vertical exaggeration for a terrain loaded at 1: 1 unless its relief rises less than
//! 4 % of its shorter side, then up to 5 in steps of 1.5, 2, 3, 4, 5.
double derive_exaggeration(const Heightfield& hf);

//! scene with every key it leaves out derived from `terrain` (loaded by load_scene_terrain, at
//! `exaggeration`), each recorded in `record` (the exaggeration too when the file left it out).
Scene derive_scene_defaults(const Scene& scene, const Terrain& terrain, double exaggeration, DerivedDefaults& record);

}  // namespace kiri::geometry
