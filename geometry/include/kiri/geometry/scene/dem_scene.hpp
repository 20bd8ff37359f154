#pragma once
//! \file dem_scene.hpp
//! Starting from a DEM: `kiri render DEM`, `kiri author DEM`, `kiri new DEM` and `kiri-preview
//! DEM` read a raster as the scene that gives only its terrain and a valley fog; the Pipeline
//! derives every other key from the terrain (scene_defaults.hpp).
#include <filesystem>

#include "kiri/geometry/scene/scene.hpp"

namespace kiri::geometry {

//! Whether path names a scene file (".json", any case) rather than a raster.
bool is_scene_path(const std::filesystem::path& path);

//! The scene of a bare DEM: {"terrain": {"path": DEM}, "fog": {"fill": {"seeds": "all"}}}: fog
//! in every low ground up to the derived top (also where valley analysis finds no valley, on a
//! plain or a single peak), every other key left to the terrain. \throw InputError naming the file when it is missing.
Scene dem_scene(const std::filesystem::path& dem);

//! load_scene for a scene file, dem_scene for anything else.
Scene load_scene_or_dem(const std::filesystem::path& path);

//! The scene as a starter file at `out`: every key spelled out (scene_to_json), the terrain's
//! path relative to out's folder when it can be.
std::string starter_scene_json(const Scene& scene, const std::filesystem::path& out);

}  // namespace kiri::geometry
