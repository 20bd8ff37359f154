#include "kiri/geometry/scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "scene/fog_spec_json.hpp"
#include "scene/layer_options_json.hpp"
#include "scene/medium_options_json.hpp"
#include "scene/particle_options_json.hpp"
#include "scene/fog_partition_json.hpp"
#include "scene/froxel_options_json.hpp"
#include "core/json_reader.hpp"
#include "kiri/geometry/terrain/dem.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/terrain/terrain.hpp"

namespace kiri::geometry {
namespace {

using json = nlohmann::json;

using Reader = JsonReader;

TerrainSpec read_terrain(const Reader& r, const json& j, const std::filesystem::path& base_dir)
{
    r.only(j, "/terrain", {"path", "exaggeration", "cell_size", "vertical_scale", "vertical_offset"});
    if (!j.contains("path"))
        r.fail("/terrain/path", "missing (the elevation raster to load)");
    TerrainSpec t;
    const std::string path = r.string(j["path"], "/terrain/path");
    if (path.empty())
        r.fail("/terrain/path", "must not be empty");
    t.path = std::filesystem::path(path).is_absolute() ? std::filesystem::path(path) : base_dir / path;
    if (j.contains("exaggeration"))
        t.exaggeration = r.in_range(j["exaggeration"], "/terrain/exaggeration", 0.0, 100.0, true);
    if (j.contains("cell_size"))
        t.cell_size = r.in_range(j["cell_size"], "/terrain/cell_size", 0.0, 1e6, false);
    if (j.contains("vertical_scale"))
        t.vertical_scale = r.in_range(j["vertical_scale"], "/terrain/vertical_scale", 0.0, 1e6, true);
    if (j.contains("vertical_offset"))
        t.vertical_offset = r.number(j["vertical_offset"], "/terrain/vertical_offset");
    return t;
}

std::vector<CameraSpec> read_cameras(const Reader& r, const json& j)
{
    if (!j.is_array())
        r.fail("/cameras", "expected an array of cameras");
    std::vector<CameraSpec> cameras;
    std::set<std::string> names;
    for (std::size_t k = 0; k < j.size(); ++k) {
        const std::string p = "/cameras/" + std::to_string(k);
        const json& c = j[k];
        r.only(c, p, {"name", "position", "target", "fov"});
        CameraSpec cam;
        if (c.contains("name"))
            cam.name = r.string(c["name"], p + "/name");
        if (!names.insert(cam.name).second)
            r.fail(p + "/name", "duplicate camera name \"" + cam.name + "\"");
        if (!c.contains("position") || !c.contains("target"))
            r.fail(p, "a camera needs \"position\" and \"target\" (local metres)");
        cam.position = r.vec3(c["position"], p + "/position");
        cam.target = r.vec3(c["target"], p + "/target");
        if (glm::dvec3 d = cam.target - cam.position; d.x == 0.0 && d.y == 0.0 && d.z == 0.0)
            r.fail(p + "/target", "equals the position: the view direction is undefined");
        if (c.contains("fov"))
            cam.fov_y_deg = r.in_range(c["fov"], p + "/fov", 0.0, 180.0, true);
        cameras.push_back(cam);
    }
    return cameras;
}

SunSpec read_sun(const Reader& r, const json& j)
{
    r.only(j, "/sun", {"direction", "color", "intensity", "ambient"});
    SunSpec s;
    if (j.contains("direction")) {
        s.direction = r.vec3(j["direction"], "/sun/direction");
        const double len =
            std::sqrt(s.direction.x * s.direction.x + s.direction.y * s.direction.y + s.direction.z * s.direction.z);
        if (!(len > 0.0))
            r.fail("/sun/direction", "must not be the zero vector");
        // Dividing a unit vector by its computed length can move its last bits; leaving
        // vectors already unit to rounding untouched makes scene_to_json -> parse exact.
        if (std::abs(len - 1.0) > 1e-14)
            s.direction /= len;
    }
    const auto colour = [&](const char* key, glm::dvec3& out) {
        if (!j.contains(key))
            return;
        const std::string p = std::string("/sun/") + key;
        out = r.vec3(j[key], p);
        if (out.x < 0.0 || out.y < 0.0 || out.z < 0.0)
            r.fail(p, "colour components must be >= 0");
    };
    colour("color", s.color);
    colour("ambient", s.ambient);
    if (j.contains("intensity"))
        s.intensity = r.in_range(j["intensity"], "/sun/intensity", 0.0, 1e6, false);
    return s;
}

ImageSpec read_image(const Reader& r, const json& j)
{
    r.only(j, "/image", {"width", "height"});
    ImageSpec im;
    if (j.contains("width"))
        im.width = r.integer(j["width"], "/image/width", 1, 16384);
    if (j.contains("height"))
        im.height = r.integer(j["height"], "/image/height", 1, 16384);
    return im;
}

// nlohmann's messages start with "[json.exception.parse_error.101] "; the rest is the useful part.
std::string strip_exception_id(std::string what)
{
    if (const auto close = what.find("] "); what.rfind("[json.exception", 0) == 0 && close != std::string::npos)
        what = what.substr(close + 2);
    return what;
}

std::string parse_error_reason(const json::parse_error& e) { return "malformed JSON: " + strip_exception_id(e.what()); }

json arr(const glm::dvec3& v) { return json::array({v.x, v.y, v.z}); }

}  // namespace

Scene parse_scene(std::string_view json_text, const std::string& file_label, const std::filesystem::path& base_dir)
{
    json root;
    try {
        root = json::parse(json_text.begin(), json_text.end());
    } catch (const json::parse_error& e) {
        throw InputError(file_label, "", parse_error_reason(e));
    } catch (const json::out_of_range& e) {
        // A number literal beyond double (e.g. 1e400): nlohmann gives no position for it.
        throw InputError(file_label, "", "malformed JSON: " + strip_exception_id(e.what()) + " (not a finite number)");
    }
    const Reader r{file_label};
    r.only(root, "",
           {"terrain", "cameras", "sun", "image", "fog", "layers", "medium", "particles", "froxel", "combined",
            "quality"});
    std::optional<Quality> quality;
    if (root.contains("quality")) {
        const json& q = root["quality"];
        Quality preset;
        if (!q.is_string() || !parse_quality(q.get<std::string>(), preset))
            r.fail("/quality", "expected \"low\", \"medium\", \"high\" or \"ultra\"");
        apply_quality_preset(root, preset);  // under the scene's own keys
        quality = preset;
    }
    if (!root.contains("terrain"))
        r.fail("/terrain", "missing (every scene needs a terrain)");
    Scene scene;
    scene.terrain = read_terrain(r, root["terrain"], base_dir);
    if (root.contains("cameras"))
        scene.cameras = read_cameras(r, root["cameras"]);
    if (root.contains("sun"))
        scene.sun = read_sun(r, root["sun"]);
    if (root.contains("image"))
        scene.image = read_image(r, root["image"]);
    if (root.contains("fog")) {
        // The fog reader throws InputError itself; a stray nlohmann exception still names the file.
        try {
            scene.fog = parse_fog_spec(root["fog"], file_label, "/fog", base_dir);
        } catch (const json::exception& e) {
            r.fail("/fog", strip_exception_id(e.what()));
        }
    }
    if (root.contains("layers"))
        scene.layers = parse_layer_options(root["layers"], file_label);
    if (root.contains("medium"))
        scene.medium = parse_medium_options(root["medium"], file_label);
    if (root.contains("particles"))
        scene.particles = parse_particle_options(root["particles"], file_label);
    if (root.contains("froxel"))
        scene.froxel = parse_froxel_options(root["froxel"], file_label);
    if (root.contains("combined"))
        scene.combined = parse_fog_partition(root["combined"], file_label);
    scene.quality = quality;
    return scene;
}

Scene load_scene(const std::filesystem::path& path)
{
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw InputError(path.string(), "", std::filesystem::exists(path, ec) ? "not a regular file" : "no such file");
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw InputError(path.string(), "", "cannot be read (permissions?)");
    // Scenes are small hand-written files; anything huge is not a scene.
    if (std::filesystem::file_size(path, ec) > (std::uintmax_t(64) << 20))
        throw LimitError(path.string(), "", "larger than 64 MiB, not a scene file");
    std::ostringstream text;
    text << in.rdbuf();
    Scene scene = parse_scene(text.str(), path.string(), path.parent_path());
    scene.file = path;
    return scene;
}

std::string scene_to_json(const Scene& scene)
{
    json root;
    json t = {{"path", scene.terrain.path.string()}, {"exaggeration", scene.terrain.exaggeration}};
    if (scene.terrain.cell_size > 0.0)
        t["cell_size"] = scene.terrain.cell_size;
    if (scene.terrain.vertical_scale != 1.0)
        t["vertical_scale"] = scene.terrain.vertical_scale;
    if (scene.terrain.vertical_offset != 0.0)
        t["vertical_offset"] = scene.terrain.vertical_offset;
    root["terrain"] = t;
    json cams = json::array();
    for (const CameraSpec& c : scene.cameras)
        cams.push_back(
            {{"name", c.name}, {"position", arr(c.position)}, {"target", arr(c.target)}, {"fov", c.fov_y_deg}});
    if (!cams.empty())
        root["cameras"] = cams;
    root["sun"] = {{"direction", arr(scene.sun.direction)},
                   {"color", arr(scene.sun.color)},
                   {"intensity", scene.sun.intensity},
                   {"ambient", arr(scene.sun.ambient)}};
    root["image"] = {{"width", scene.image.width}, {"height", scene.image.height}};
    if (scene.fog)
        root["fog"] = fog_spec_to_json(*scene.fog);
    root["layers"] = layer_options_to_json(scene.layers);
    root["medium"] = medium_options_to_json(scene.medium);
    root["particles"] = particle_options_to_json(scene.particles);
    root["froxel"] = froxel_options_to_json(scene.froxel);
    root["combined"] = fog_partition_to_json(scene.combined);
    if (scene.quality)  // every key is written too, so the preset changes nothing on reading
        root["quality"] = to_string(*scene.quality);
    return root.dump(2) + "\n";
}

CameraSpec Scene::camera(std::string_view name, const glm::dvec3& lo, const glm::dvec3& hi) const
{
    if (!name.empty()) {
        for (const CameraSpec& c : cameras)
            if (c.name == name)
                return c;
        std::string known;
        for (const CameraSpec& c : cameras)
            known += (known.empty() ? "" : ", ") + c.name;
        throw InputError(file.string(), "/cameras",
                         "no camera named \"" + std::string(name) + "\"" +
                             (known.empty() ? " (the scene has none)" : " (cameras: " + known + ")"));
    }
    if (!cameras.empty())
        return cameras.front();
    // No camera: look at the terrain's centre from the south-west, 35 degrees down, far enough
    // for the whole extent to fit a 45 degree view.
    const glm::dvec3 centre = 0.5 * (lo + hi);
    const double radius =
        0.5 * std::sqrt((hi.x - lo.x) * (hi.x - lo.x) + (hi.y - lo.y) * (hi.y - lo.y) + (hi.z - lo.z) * (hi.z - lo.z));
    const double distance = std::max(radius, 1.0) / std::sin(22.5 * M_PI / 180.0);
    const double down = 35.0 * M_PI / 180.0;
    CameraSpec c;
    c.name = "auto";
    c.target = centre;
    c.position = centre +
        distance * glm::dvec3(-std::cos(down) * std::sqrt(0.5), -std::cos(down) * std::sqrt(0.5), std::sin(down));
    c.fov_y_deg = 45.0;
    return c;
}

Terrain load_scene_terrain(const Scene& scene)
{
    DemOptions options;
    options.cell_size = scene.terrain.cell_size;
    options.vertical_scale = scene.terrain.vertical_scale;
    options.vertical_offset = scene.terrain.vertical_offset;
    options.exaggeration = scene.terrain.exaggeration;
    return Terrain(load_dem(scene.terrain.path, options));
}

FogSpec world_fog_spec(const Scene& scene)
{
    if (!scene.fog)
        throw InputError(scene.file.string(), "/fog", "the scene has no fog section");
    FogSpec spec = *scene.fog;
    const double e = scene.terrain.exaggeration;
    spec.fit.altitude *= e;
    spec.fit.offset *= e;
    spec.fit.clearance *= e;
    spec.fit.thickness *= e;
    if (spec.placement) {
        spec.placement->exaggeration = e;
        for (FillRegionSpec& r : spec.placement->regions) {
            r.top *= e;
            r.min_thickness *= e;
            r.max_thickness *= e;
        }
        if (spec.placement->flow) {
            // Without its own depth, the flow evaporates as the scene's medium holds water.
            if (!spec.placement->evaporation_given)
                spec.placement->flow->evaporation_depth = evaporation_depth_for(scene.medium.extinction);
            spec.placement->flow->evaporation_depth *= e;
            spec.placement->flow->min_thickness *= e;
        }
        if (spec.placement->burn_off) {
            spec.placement->burn_off->burn_rate *= e;
            spec.placement->burn_off->lift_rate *= e;
            spec.placement->burn_off->min_thickness *= e;
            // The optics of the scene's medium, per world metre (heights are stretched by e).
            spec.placement->burn_off->extinction = scene.medium.extinction / e;
            spec.placement->burn_off->anisotropy = std::clamp(scene.medium.anisotropy, 0.0, 0.99);
        }
    }
    return spec;
}

LayerOptions world_layer_options(const Scene& scene)
{
    LayerOptions options = scene.layers;
    const double e = scene.terrain.exaggeration;
    options.thickness = (scene.fog ? scene.fog->fit.thickness : FitOptions{}.thickness) * e;
    options.ground_fade *= e;
    options.optics = scene.medium;
    validate_layer_options(options, scene.file.string());
    return options;
}

FroxelOptions world_froxel_options(const Scene& scene)
{
    FroxelOptions options = scene.froxel;
    const double e = scene.terrain.exaggeration;
    options.height_fog.base *= e;
    options.height_fog.scale_height *= e;
    validate_froxel_options(options, scene.file.string());
    return options;
}

}  // namespace kiri::geometry
