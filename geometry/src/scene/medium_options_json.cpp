#include "scene/medium_options_json.hpp"

#include "core/json_reader.hpp"

namespace kiri::geometry {

using json = nlohmann::json;

namespace {

// The medium's motion: its own keys, and the layers' before the medium owned them.
void read_medium_motion(const json& j, const JsonReader& r, const std::string& p, MediumOptions& o)
{
    if (j.contains("detail"))
        o.detail = r.in_range(j["detail"], p + "/detail", 0.0, 1.0, false);
    if (j.contains("detail_scale"))
        o.detail_scale = r.positive(j["detail_scale"], p + "/detail_scale");
    if (j.contains("dissipation_half_life"))
        o.dissipation_half_life = r.non_negative(j["dissipation_half_life"], p + "/dissipation_half_life");
    if (j.contains("wind"))
        o.wind = r.point(j["wind"], p + "/wind");
    if (j.contains("time"))
        o.time = r.number(j["time"], p + "/time");
}

}  // namespace

MediumOptions parse_medium_options(const json& j, const std::string& file)
{
    const JsonReader r{file};
    const std::string p = "/medium";
    r.only(j, p,
           {"extinction", "visibility", "liquid_water_content", "droplet_radius", "albedo", "anisotropy", "top_density",
            "grid_spacing", "max_grid_side", "scattering_octaves", "detail", "detail_scale", "wind", "time",
            "dissipation_half_life"});
    const int given =
        int(j.contains("extinction")) + int(j.contains("visibility")) + int(j.contains("liquid_water_content"));
    if (given > 1)
        r.fail(p, "give only one of extinction, visibility and liquid_water_content (each sets the extinction)");
    if (j.contains("droplet_radius") && !j.contains("liquid_water_content"))
        r.fail(p + "/droplet_radius", "only used with liquid_water_content");
    MediumOptions o;
    if (j.contains("extinction"))
        o.extinction = r.positive(j["extinction"], p + "/extinction");
    if (j.contains("visibility"))
        o.extinction = extinction_from_visibility(r.positive(j["visibility"], p + "/visibility"));
    if (j.contains("liquid_water_content")) {
        const double lwc = r.positive(j["liquid_water_content"], p + "/liquid_water_content");
        const double radius =
            j.contains("droplet_radius") ? r.positive(j["droplet_radius"], p + "/droplet_radius") : 7.0;
        o.extinction = extinction_from_liquid_water(lwc, radius);
    }
    if (o.extinction > 1e3)  // a visibility of 4 mm: no fog is that dense, and the renderers' steps lose it
        r.fail(p, "extinction above 1000 1/m (visibility under 4 mm)");
    if (j.contains("albedo"))
        o.albedo = r.in_range(j["albedo"], p + "/albedo", 0.0, 1.0, false);
    if (j.contains("anisotropy"))
        o.anisotropy = r.in_range(j["anisotropy"], p + "/anisotropy", -1.0, 1.0, true);
    if (j.contains("top_density"))
        o.top_density = r.in_range(j["top_density"], p + "/top_density", 0.0, 1.0, false);
    if (j.contains("grid_spacing"))
        o.grid_spacing = r.non_negative(j["grid_spacing"], p + "/grid_spacing");
    if (j.contains("max_grid_side"))
        o.max_grid_side = r.integer(j["max_grid_side"], p + "/max_grid_side", 2, 8192);
    if (j.contains("scattering_octaves"))
        o.scattering_octaves = r.integer(j["scattering_octaves"], p + "/scattering_octaves", 1, 8);
    read_medium_motion(j, r, p, o);
    return o;
}

void read_layer_aliases(const json& layers, const json* medium, const std::string& file, MediumOptions& o)
{
    const JsonReader r{file};
    json given = json::object();
    for (const char* key : {"detail", "detail_scale", "wind", "time", "dissipation_half_life"}) {
        if (!layers.contains(key))
            continue;
        if (medium && medium->contains(key))
            r.fail(std::string("/layers/") + key,
                   std::string("the old name of /medium/") + key + ", which the scene gives too: give only that");
        given[key] = layers[key];
    }
    read_medium_motion(given, r, "/layers", o);
}

json medium_options_to_json(const MediumOptions& o)
{
    return {{"extinction", o.extinction},
            {"albedo", o.albedo},
            {"anisotropy", o.anisotropy},
            {"top_density", o.top_density},
            {"grid_spacing", o.grid_spacing},
            {"max_grid_side", o.max_grid_side},
            {"scattering_octaves", o.scattering_octaves},
            {"detail", o.detail},
            {"detail_scale", o.detail_scale},
            {"dissipation_half_life", o.dissipation_half_life},
            {"wind", {o.wind.x, o.wind.y}},
            {"time", o.time}};
}

}  // namespace kiri::geometry
