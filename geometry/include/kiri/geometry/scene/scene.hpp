#pragma once
//! \file scene.hpp
//! The scene file (JSON): what a user authors. Later stages extend this schema; every key
//! is documented in docs/scene.md. Unknown keys are errors.
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "kiri/geometry/core/fields.hpp"
#include "kiri/geometry/scene/fog_spec.hpp"
#include "kiri/geometry/medium/fog_partition.hpp"
#include "kiri/geometry/volume/froxel_options.hpp"
#include "kiri/geometry/scene/quality.hpp"
#include "kiri/geometry/layers/layer_stack.hpp"
#include "kiri/geometry/medium/medium.hpp"
#include "kiri/geometry/particles/particles.hpp"

namespace kiri::geometry {

struct TerrainSpec {
    std::filesystem::path path;  //!< resolved against the scene file's folder
    double exaggeration = 1.0;
    double cell_size = 0.0;
    double vertical_scale = 1.0;
    double vertical_offset = 0.0;
    bool surround = true;  //!< the ground beyond the DEM's edge (terrain/ground.hpp), in every renderer
    bool operator==(const TerrainSpec&) const = default;
};

template <fields_of<TerrainSpec> O, class V>
void visit_fields(O& o, V&& v)
{
    v(o.path,
      {.key = "path",
       .doc = "elevation raster (GeoTIFF, ESRI ASCII grid, SRTM `.hgt`, 8/16-bit PNG), or scattered points "
              "(`.xyz`, `.csv`, `.txt`: x y z rows in metres, triangulated and resampled every `cell_size`); a "
              "relative path is resolved against the **scene file's folder**, not the working directory",
       .required = "missing (the elevation raster to load)"});
    v(o.exaggeration,
      {.key = "exaggeration",
       .range = open_range(0, 100),
       .doc = "vertical exaggeration applied to every height on load",
       .widget = closed(0.1, 10),
       .log_widget = true});
    v(o.cell_size,
      {.key = "cell_size",
       .unit = "m",
       .range = closed(0, 1e6),
       .doc = "per cell, for rasters without georeferencing (PNG heightmaps) and points; 0 = take it from the "
              "raster, or about one point a cell",
       .widget = closed(0, 1000),
       .omit_default = true});
    v(o.vertical_scale,
      {.key = "vertical_scale",
       .unit = "m/unit",
       .range = open_range(0, 1e6),
       .doc = "metres per raster unit (PNG heightmaps)",
       .widget = closed(1e-3, 1e3),
       .log_widget = true,
       .omit_default = true});
    v(o.vertical_offset,
      {.key = "vertical_offset",
       .unit = "m",
       .doc = "added to every height (before the exaggeration)",
       .omit_default = true});
    v(o.surround,
      {.key = "surround",
       .doc = "the ground continues beyond the DEM's edge (its edge eased to the border's median height, then flat "
              "to the horizon; the sea to the horizon on a coast), drawn by every renderer; false: the bare tile",
       .omit_default = true});
}

struct CameraSpec {
    std::string name = "default";
    glm::dvec3 position{0.0, -5000.0, 3000.0};  //!< local metres
    glm::dvec3 target{0.0, 0.0, 500.0};
    double fov_y_deg = 45.0;  //!< vertical
    bool operator==(const CameraSpec&) const = default;
};

//! One camera of the "cameras" array: names are unique, the target is not the position.
template <fields_of<CameraSpec> O, class V>
void visit_fields(O& o, V&& v)
{
    v(o.name, {.key = "name", .doc = "unique within the scene; `kiri render --camera NAME` picks one"});
    v(o.position,
      {.key = "position", .unit = "m", .doc = "eye, local metres", .shown_default = "required", .shape = "[x, y, z]"});
    v(o.target,
      {.key = "target",
       .unit = "m",
       .doc = "point looked at; must differ from `position`",
       .shown_default = "required",
       .shape = "[x, y, z]"});
    v(o.fov_y_deg, {.key = "fov", .unit = "deg", .range = open_range(0, 180), .doc = "vertical field of view"});
}

struct SunSpec {
    glm::dvec3 direction{0.5, -0.3, 0.6};  //!< towards the sun (normalised on load)
    glm::dvec3 color{1.0, 0.96, 0.9};
    double intensity = 3.0;
    glm::dvec3 ambient{0.25, 0.3, 0.38};
    bool operator==(const SunSpec&) const = default;
};

template <fields_of<SunSpec> O, class V>
void visit_fields(O& o, V&& v)
{
    v(o.direction, {.key = "direction", .doc = "towards the sun, not zero; normalised on load", .shape = "[x, y, z]"});
    v(o.color, {.key = "color", .range = at_least(0), .doc = "sun colour (linear)", .shape = "[r, g, b]"});
    v(o.intensity, {.key = "intensity", .range = closed(0, 1e6), .doc = "sun radiance scale", .widget = closed(0, 20)});
    v(o.ambient, {.key = "ambient", .range = at_least(0), .doc = "sky ambient radiance", .shape = "[r, g, b]"});
}

struct ImageSpec {
    int width = 1280, height = 720;
    bool operator==(const ImageSpec&) const = default;
};

template <fields_of<ImageSpec> O, class V>
void visit_fields(O& o, V&& v)
{
    v(o.width, {.key = "width", .unit = "px", .range = closed(1, 16384), .doc = "`kiri render --width` overrides it"});
    v(o.height,
      {.key = "height", .unit = "px", .range = closed(1, 16384), .doc = "`kiri render --height` overrides it"});
}

struct Scene {
    std::filesystem::path file;  //!< where it was loaded from (for messages); may be empty
    TerrainSpec terrain;
    std::vector<CameraSpec> cameras;  //!< may be empty: renderers then frame the terrain
    SunSpec sun;
    ImageSpec image;
    std::optional<FogSpec> fog;  //!< the "fog" section (docs/scene.md), if any
    LayerOptions layers;         //!< the "layers" section (defaults when absent)
    MediumOptions medium;        //!< the "medium" section (defaults when absent)
    ParticleOptions particles;   //!< the "particles" section (defaults when absent)
    FroxelOptions froxel;        //!< the "froxel" section (defaults when absent)
    FogPartition combined;       //!< the "combined" section: each renderer's share in combined mode
    //! The "quality" key (quality.hpp): the preset applied under the scene's own keys; kept so
    //! that a saved scene names it.
    std::optional<Quality> quality;
    //! The JSON pointers of every key the file gave ("/terrain/exaggeration", "/fog/fill/0/top";
    //! a quality preset's keys count as given). The Pipeline derives the keys left out from the
    //! terrain (scene_defaults.hpp). Unset for a scene built in code: every value is as set.
    std::optional<std::set<std::string>> given;
    bool gives(std::string_view pointer) const { return !given || given->count(std::string(pointer)) > 0; }

    //! The camera called name; the first when name is empty; a view framing `terrain_bounds`
    //! (min, max) from the south-west when the scene has no camera and name is empty.
    //! \throw InputError naming /cameras if a named camera is absent.
    CameraSpec camera(std::string_view name, const glm::dvec3& terrain_min, const glm::dvec3& terrain_max) const;
    bool operator==(const Scene&) const = default;
};

//! \throw InputError "FILE: /json/pointer: reason" on any problem.
Scene load_scene(const std::filesystem::path& path);
//! Parses JSON text; file_label names it in messages, base_dir resolves relative paths.
Scene parse_scene(std::string_view json_text, const std::string& file_label, const std::filesystem::path& base_dir);
//! Writes the scene back as JSON that parse_scene reads to an equal Scene.
std::string scene_to_json(const Scene& scene);

class Terrain;
//! Loads the scene's terrain in world units: heights in metres times the vertical
//! exaggeration, so every stage (fit, layers, renderers) sees the same exaggerated ground. When
//! the scene leaves the exaggeration out (Scene::given), it is derived from the relief
//! (derive_exaggeration, scene_defaults.hpp) and stored in *exaggeration.
Terrain load_scene_terrain(const Scene& scene, double* exaggeration = nullptr);

//! The scene's fog section in world units: its vertical quantities (lake altitude, offset,
//! clearance, thickness) are written in metres of the DEM and stretched here by the vertical
//! exaggeration, like the terrain. \throw InputError naming /fog when the scene has none.
FogSpec world_fog_spec(const Scene& scene);
//! The scene's layer options in world units: thickness = fog.thickness and ground_fade
//! stretched by the exaggeration. \throw InputError naming /layers on options out of range.
LayerOptions world_layer_options(const Scene& scene);
//! The scene's froxel options in world units: the height fog's base and scale height stretched
//! by the exaggeration. \throw InputError naming /froxel on options out of range.
FroxelOptions world_froxel_options(const Scene& scene);

}  // namespace kiri::geometry
