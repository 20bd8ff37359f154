#include "scene/froxel_options_json.hpp"

#include "kiri/geometry/medium/medium.hpp"
#include "core/json_reader.hpp"

namespace kiri::geometry {

using json = nlohmann::json;

namespace {

HeightFog parse_height_fog(const json& j, const JsonReader& r)
{
    const std::string p = "/froxel/height_fog";
    r.only(j, p, {"extinction", "visibility", "base", "scale_height", "albedo", "anisotropy"});
    if (j.contains("extinction") && j.contains("visibility"))
        r.fail(p, "give only one of extinction and visibility");
    HeightFog f;
    if (j.contains("extinction"))
        f.extinction = r.in_range(j["extinction"], p + "/extinction", 0.0, 1e3, false);
    if (j.contains("visibility"))
        f.extinction = extinction_from_visibility(r.positive(j["visibility"], p + "/visibility"));
    if (j.contains("base"))
        f.base = r.number(j["base"], p + "/base");
    if (j.contains("scale_height"))
        f.scale_height = r.positive(j["scale_height"], p + "/scale_height");
    if (j.contains("albedo"))
        f.albedo = r.in_range(j["albedo"], p + "/albedo", 0.0, 1.0, false);
    if (j.contains("anisotropy"))
        f.anisotropy = r.in_range(j["anisotropy"], p + "/anisotropy", -1.0, 1.0, true);
    return f;
}

}  // namespace

FroxelOptions parse_froxel_options(const json& j, const std::string& file)
{
    const JsonReader r{file};
    const std::string p = "/froxel";
    r.only(j, p,
           {"size", "distribution", "power", "log2_scale", "near", "far", "fog_aware", "temporal", "history_weight",
            "density_samples", "sun_steps", "pixel_steps", "terrain_shadows", "fog_shadows", "shadow_map_size",
            "esm_sharpness", "height_fog"});
    FroxelOptions o;
    if (j.contains("size")) {
        const json& s = j["size"];
        if (!s.is_array() || s.size() != 3)
            r.fail(p + "/size", "expected an array of 3 integers [width, height, slices]");
        o.width = r.integer(s[0], p + "/size/0", 1, 1024);
        o.height = r.integer(s[1], p + "/size/1", 1, 1024);
        o.slices = r.integer(s[2], p + "/size/2", 2, 512);
    }
    if (j.contains("distribution")) {
        const std::string name = r.string(j["distribution"], p + "/distribution");
        if (!parse_slice_distribution(name, o.distribution))
            r.fail(p + "/distribution", "expected \"exponential\", \"log2\" or \"power\", got \"" + name + "\"");
    }
    if (j.contains("power"))
        o.power = r.in_range(j["power"], p + "/power", 0.0, 16.0, false);
    if (o.power == 0.0)
        r.fail(p + "/power", "must be > 0");
    if (j.contains("log2_scale"))
        o.log2_scale = r.positive(j["log2_scale"], p + "/log2_scale");
    if (j.contains("near"))
        o.near = r.positive(j["near"], p + "/near");
    if (j.contains("far"))
        o.far = r.non_negative(j["far"], p + "/far");
    if (o.far > 0.0 && o.far <= o.near)
        r.fail(p + "/far", "must be 0 (the scene's far side) or larger than near");
    if (j.contains("fog_aware"))
        o.fog_aware = r.boolean(j["fog_aware"], p + "/fog_aware");
    if (j.contains("temporal"))
        o.temporal = r.boolean(j["temporal"], p + "/temporal");
    if (j.contains("history_weight"))
        o.history_weight = r.in_range(j["history_weight"], p + "/history_weight", 0.0, 0.99, false);
    if (j.contains("density_samples"))
        o.density_samples = r.integer(j["density_samples"], p + "/density_samples", 1, 16);
    if (j.contains("sun_steps"))
        o.sun_steps = r.integer(j["sun_steps"], p + "/sun_steps", 1, 64);
    if (j.contains("pixel_steps"))
        o.pixel_steps = r.integer(j["pixel_steps"], p + "/pixel_steps", 1, 256);
    if (j.contains("terrain_shadows"))
        o.terrain_shadows = r.boolean(j["terrain_shadows"], p + "/terrain_shadows");
    if (j.contains("fog_shadows"))
        o.fog_shadows = r.boolean(j["fog_shadows"], p + "/fog_shadows");
    if (j.contains("shadow_map_size"))
        o.shadow_map_size = r.integer(j["shadow_map_size"], p + "/shadow_map_size", 64, 8192);
    if (j.contains("esm_sharpness"))
        o.esm_sharpness = r.in_range(j["esm_sharpness"], p + "/esm_sharpness", 0.0, 64.0, false);
    if (o.esm_sharpness == 0.0)
        r.fail(p + "/esm_sharpness", "must be > 0");
    if (j.contains("height_fog"))
        o.height_fog = parse_height_fog(j["height_fog"], r);
    return o;
}

json froxel_options_to_json(const FroxelOptions& o)
{
    const HeightFog& h = o.height_fog;
    return {{"size", {o.width, o.height, o.slices}},
            {"distribution", to_string(o.distribution)},
            {"power", o.power},
            {"log2_scale", o.log2_scale},
            {"near", o.near},
            {"far", o.far},
            {"fog_aware", o.fog_aware},
            {"temporal", o.temporal},
            {"history_weight", o.history_weight},
            {"density_samples", o.density_samples},
            {"sun_steps", o.sun_steps},
            {"pixel_steps", o.pixel_steps},
            {"terrain_shadows", o.terrain_shadows},
            {"fog_shadows", o.fog_shadows},
            {"shadow_map_size", o.shadow_map_size},
            {"esm_sharpness", o.esm_sharpness},
            {"height_fog",
             {{"extinction", h.extinction},
              {"base", h.base},
              {"scale_height", h.scale_height},
              {"albedo", h.albedo},
              {"anisotropy", h.anisotropy}}}};
}

}  // namespace kiri::geometry
