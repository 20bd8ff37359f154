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
#include "scene/field_json.hpp"
#include "scene/quality_json.hpp"
#include "kiri/geometry/terrain/dem.hpp"
#include "kiri/geometry/terrain/point_files.hpp"
#include "kiri/geometry/terrain/scattered_points.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/terrain/terrain.hpp"
#include "kiri/geometry/scene/scene_defaults.hpp"

namespace kiri::geometry {
namespace {

using json = nlohmann::json;

using Reader = JsonReader;

TerrainSpec read_terrain(const Reader& r, const json& j, const std::filesystem::path& base_dir)
{
    TerrainSpec t;
    read_fields(r, j, "/terrain", t, {}, base_dir);
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
        CameraSpec cam;
        const std::string position(field_of(cam, cam.position).key), target(field_of(cam, cam.target).key);
        read_fields(r, c, p, cam);
        if (!c.contains(position) || !c.contains(target))
            r.fail(p, "a camera needs \"position\" and \"target\" (local metres)");
        if (!names.insert(cam.name).second)
            r.fail(p + "/name", "duplicate camera name \"" + cam.name + "\"");
        if (glm::dvec3 d = cam.target - cam.position; d.x == 0.0 && d.y == 0.0 && d.z == 0.0)
            r.fail(p + "/" + target, "equals the position: the view direction is undefined");
        cameras.push_back(cam);
    }
    return cameras;
}

SunSpec read_sun(const Reader& r, const json& j)
{
    SunSpec s;
    read_fields(r, j, "/sun", s);
    if (const std::string key(field_of(s, s.direction).key); j.contains(key)) {
        const double len =
            std::sqrt(s.direction.x * s.direction.x + s.direction.y * s.direction.y + s.direction.z * s.direction.z);
        if (!(len > 0.0))
            r.fail("/sun/" + key, "must not be the zero vector");
        // Dividing a unit vector by its computed length can move its last bits; leaving
        // vectors already unit to rounding untouched makes scene_to_json -> parse exact.
        if (std::abs(len - 1.0) > 1e-14)
            s.direction /= len;
    }
    return s;
}

ImageSpec read_image(const Reader& r, const json& j)
{
    ImageSpec im;
    read_fields(r, j, "/image", im);
    return im;
}

// nlohmann's messages start with "[json.exception.parse_error.101] "; the rest is the useful part.
std::string strip_exception_id(std::string what)
{
    if (const auto close = what.find("] "); what.rfind("[json.exception", 0) == 0 && close != std::string::npos)
        what = what.substr(close + 2);
    return what;
}

// Every key and array element of j, as JSON pointers under prefix.
void record_given(const json& j, const std::string& prefix, std::set<std::string>& given)
{
    if (j.is_object()) {
        for (const auto& [key, value] : j.items()) {
            given.insert(prefix + "/" + key);
            record_given(value, prefix + "/" + key, given);
        }
    } else if (j.is_array()) {
        for (std::size_t k = 0; k < j.size(); ++k) {
            given.insert(prefix + "/" + std::to_string(k));
            record_given(j[k], prefix + "/" + std::to_string(k), given);
        }
    }
}

std::string parse_error_reason(const json::parse_error& e) { return "malformed JSON: " + strip_exception_id(e.what()); }

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
    if (root.contains("medium"))
        scene.medium = parse_medium_options(root["medium"], file_label);
    if (root.contains("layers")) {
        scene.layers = parse_layer_options(root["layers"], file_label, medium_keys_in_layers());
        read_layer_aliases(root["layers"], root.contains("medium") ? &root["medium"] : nullptr, file_label,
                           scene.medium);
    }
    if (root.contains("particles"))
        scene.particles = parse_particle_options(root["particles"], file_label);
    if (root.contains("froxel"))
        scene.froxel = parse_froxel_options(root["froxel"], file_label);
    if (root.contains("combined"))
        scene.combined = parse_fog_partition(root["combined"], file_label);
    scene.quality = quality;
    scene.given.emplace();
    record_given(root, "", *scene.given);
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
    root["terrain"] = write_fields(scene.terrain);
    json cams = json::array();
    for (const CameraSpec& c : scene.cameras)
        cams.push_back(write_fields(c));
    if (!cams.empty())
        root["cameras"] = cams;
    root["sun"] = write_fields(scene.sun);
    root["image"] = write_fields(scene.image);
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

Terrain load_scene_terrain(const Scene& scene, double* exaggeration)
{
    DemOptions options;
    options.cell_size = scene.terrain.cell_size;
    options.vertical_scale = scene.terrain.vertical_scale;
    options.vertical_offset = scene.terrain.vertical_offset;
    const bool derived =
        !scene.gives("/terrain/exaggeration") && scene.terrain.exaggeration == TerrainSpec{}.exaggeration;
    // A derived exaggeration is the relief's at 1: loaded at 1, stretched here (not loaded twice).
    options.exaggeration = derived ? 1.0 : scene.terrain.exaggeration;
    Heightfield hf;
    if (is_point_file(scene.terrain.path)) {
        // Scattered points: triangulated and resampled to the grid the rest of kiri uses, at the
        // scene's cell size or about one point a cell.
        const std::vector<glm::dvec3> points = read_points(scene.terrain.path);
        if (points.size() < 3)
            throw InputError(scene.terrain.path.string(), "", "needs at least 3 points");
        hf = heightfield_from_points(points, options.cell_size > 0.0 ? options.cell_size : point_cell_size(points));
        const double scale = options.vertical_scale * options.exaggeration;
        for (double& z : hf.z)
            z = z * scale + options.vertical_offset * options.exaggeration;
    } else {
        hf = load_dem(scene.terrain.path, options);
    }
    double e = options.exaggeration;
    if (derived) {
        e = derive_exaggeration(hf);
        if (e != 1.0)
            for (double& z : hf.z)
                z *= e;
    }
    if (exaggeration)
        *exaggeration = e;
    return Terrain(std::move(hf));
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
