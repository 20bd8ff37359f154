#include "scene/placement_json.hpp"

#include <cmath>

#include "kiri/geometry/fog/base_surface.hpp"
#include "scene/field_json.hpp"

namespace kiri::geometry {
namespace {

using json = nlohmann::json;

FillRegionSpec read_region(const json& j, const JsonReader& r, const std::string& p,
                           const std::filesystem::path& base_dir)
{
    FillRegionSpec s;
    read_fields(r, j, p, s);
    if (!j.contains("seeds"))
        r.fail(p + "/seeds",
               "missing: seed points [[x, y], ...] (local metres), \"all\", \"valleys\" or {\"mask\": FILE}");
    const json& seeds = j["seeds"];
    const std::string sp = p + "/seeds";
    if (seeds.is_array()) {
        if (seeds.empty())
            r.fail(sp, "needs at least one seed point [x, y]");
        for (std::size_t k = 0; k < seeds.size(); ++k)
            s.points.push_back(r.point(seeds[k], sp + "/" + std::to_string(k)));
    } else if (seeds == "all") {
        s.seeds = SeedKind::all;
    } else if (seeds == "valleys") {
        s.seeds = SeedKind::valleys;
    } else if (seeds.is_object()) {
        r.only(seeds, sp, {"mask"});
        if (!seeds.contains("mask"))
            r.fail(sp + "/mask", "missing: the mask raster (nonzero pixels seed the fill)");
        read_value(r, seeds["mask"], sp + "/mask", FieldInfo{}, s.mask_path, base_dir);
        s.seeds = SeedKind::mask;
    } else {
        r.fail(sp, "expected seed points [[x, y], ...], \"all\", \"valleys\" or {\"mask\": FILE}");
    }
    if (j.contains("valleys")) {
        const std::string vp = p + "/valleys";
        if (s.seeds != SeedKind::valleys)
            r.fail(vp, "only used with \"seeds\": \"valleys\"");
        const json& v = j["valleys"];
        read_fields(r, v, vp, s.valleys);
        if (v.contains("radii")) {
            const json& radii = v["radii"];
            if (!radii.is_array() || radii.empty() || radii.size() > 8)
                r.fail(vp + "/radii", "expected an array of 1 to 8 radii (metres)");
            const FieldInfo radius = field_named(s.valleys, "radii");
            for (std::size_t k = 0; k < radii.size(); ++k)
                read_value(r, radii[k], vp + "/radii/" + std::to_string(k), radius, s.valleys.radii.emplace_back());
        }
    }
    if (s.max_thickness > 0.0 && s.max_thickness <= s.min_thickness)
        r.fail(p + "/max_thickness", "must be 0 (no limit) or larger than min_thickness");
    return s;
}

FlowOptions read_flow(const json& j, const JsonReader& r, const std::string& p, bool& evaporation_given)
{
    FlowOptions o;
    read_fields(r, j, p, o);
    if (std::hypot(o.wind.x, o.wind.y) > 100.0)
        r.fail(p + "/wind", "must be at most 100 m/s");
    if (o.duration / o.time_step > 1e6)
        r.fail(p + "/time_step", "more than a million steps: take a longer time step (any is stable)");
    evaporation_given = j.contains(std::string(field_of(o, o.evaporation_depth).key));
    return o;
}

BurnOffOptions read_burn_off(const json& j, const JsonReader& r, const std::string& p, bool& latitude_given)
{
    BurnOffOptions o;
    read_fields(r, j, p, o);
    latitude_given = j.contains(std::string(field_of(o, o.latitude).key));
    return o;
}

json point_array(const std::vector<glm::dvec2>& points)
{
    json a = json::array();
    for (const glm::dvec2& q : points)
        a.push_back({q.x, q.y});
    return a;
}

}  // namespace

std::vector<std::string> keys_set_by_fill()
{
    FitOptions fit;
    return {"footprint",
            std::string(field_of(fit, fit.mode).key),
            std::string(field_of(fit, fit.altitude).key),
            std::string(field_of(fit, fit.thickness).key),
            std::string(field_of(fit, fit.offset).key),
            std::string(field_of(fit, fit.smoothing_length).key),
            std::string(field_of(fit, fit.clearance).key)};
}

std::optional<PlacementSpec> parse_placement(const json& fog, const JsonReader& r, const std::string& p,
                                             const std::filesystem::path& base_dir)
{
    if (!fog.contains("fill")) {
        for (const char* key : {"outline", "flow", "burn_off"})
            if (fog.contains(key))
                r.fail(p + "/" + key, "needs /fog/fill: the fog placed by the terrain that this acts on");
        return std::nullopt;
    }
    for (const std::string& key : keys_set_by_fill())
        if (fog.contains(key))
            r.fail(
                p + "/" + key,
                std::string("a fill sets this itself (a lake at the fog top over the footprint the terrain gives): ") +
                    "leave it out, or leave out /fog/fill");
    PlacementSpec s;
    const json& fill = fog["fill"];
    const std::string fp = p + "/fill";
    if (fill.is_array()) {
        if (fill.empty() || fill.size() > 64)
            r.fail(fp, "expected 1 to 64 regions");
        for (std::size_t k = 0; k < fill.size(); ++k)
            s.regions.push_back(read_region(fill[k], r, fp + "/" + std::to_string(k), base_dir));
    } else {
        s.regions.push_back(read_region(fill, r, fp, base_dir));
    }
    if (fog.contains("outline"))
        read_fields(r, fog["outline"], p + "/outline", s, {}, {}, OutlineFields{});
    if (fog.contains("flow"))
        s.flow = read_flow(fog["flow"], r, p + "/flow", s.evaporation_given);
    if (fog.contains("burn_off"))
        s.burn_off = read_burn_off(fog["burn_off"], r, p + "/burn_off", s.latitude_given);
    return s;
}

void placement_to_json(const PlacementSpec& s, json& fog)
{
    json regions = json::array();
    for (const FillRegionSpec& g : s.regions) {
        json j = write_fields(g);
        switch (g.seeds) {
        case SeedKind::points: j["seeds"] = point_array(g.points); break;
        case SeedKind::all: j["seeds"] = "all"; break;
        case SeedKind::valleys:
            j["seeds"] = "valleys";
            j["valleys"] = write_fields(g.valleys);
            if (!g.valleys.radii.empty())
                j["valleys"]["radii"] = g.valleys.radii;
            break;
        case SeedKind::mask: j["seeds"] = {{"mask", g.mask_path.string()}}; break;
        }
        regions.push_back(j);
    }
    fog["fill"] = regions.size() == 1 ? regions[0] : regions;
    fog["outline"] = write_fields(s, OutlineFields{});
    if (s.flow) {
        fog["flow"] = write_fields(*s.flow);
        if (!s.evaporation_given)
            fog["flow"].erase(std::string(field_of(*s.flow, s.flow->evaporation_depth).key));
    }
    if (s.burn_off) {
        fog["burn_off"] = write_fields(*s.burn_off);
        if (!s.latitude_given)
            fog["burn_off"].erase(std::string(field_of(*s.burn_off, s.burn_off->latitude).key));
    }
}

}  // namespace kiri::geometry
