#include "scene/medium_options_json.hpp"

#include "core/json_reader.hpp"

namespace kiri::geometry {

using json = nlohmann::json;

MediumOptions parse_medium_options(const json& j, const std::string& file)
{
    const JsonReader r{file};
    const std::string p = "/medium";
    r.only(j, p,
           {"extinction", "visibility", "liquid_water_content", "droplet_radius", "albedo", "anisotropy", "top_density",
            "grid_spacing", "max_grid_side", "scattering_octaves"});
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
    return o;
}

json medium_options_to_json(const MediumOptions& o)
{
    return {{"extinction", o.extinction},
            {"albedo", o.albedo},
            {"anisotropy", o.anisotropy},
            {"top_density", o.top_density},
            {"grid_spacing", o.grid_spacing},
            {"max_grid_side", o.max_grid_side},
            {"scattering_octaves", o.scattering_octaves}};
}

}  // namespace kiri::geometry
