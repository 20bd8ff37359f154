#include "scene/placement_json.hpp"

#include <cmath>

namespace kiri::geometry {
namespace {

using json = nlohmann::json;

FillRegionSpec read_region(const json& j, const JsonReader& r, const std::string& p,
                           const std::filesystem::path& base_dir)
{
    r.only(j, p, {"top", "seeds", "valleys", "min_thickness", "max_thickness", "profile"});
    FillRegionSpec s;
    if (!j.contains("top"))
        r.fail(p + "/top", "missing: the fog-top altitude (metres of the DEM), the inversion the fog fills up to");
    s.top = r.number(j["top"], p + "/top");
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
        const std::string path = r.string(seeds["mask"], sp + "/mask");
        if (path.empty())
            r.fail(sp + "/mask", "must not be empty");
        s.seeds = SeedKind::mask;
        s.mask_path = std::filesystem::path(path).is_absolute() ? std::filesystem::path(path) : base_dir / path;
    } else {
        r.fail(sp, "expected seed points [[x, y], ...], \"all\", \"valleys\" or {\"mask\": FILE}");
    }
    if (j.contains("valleys")) {
        const std::string vp = p + "/valleys";
        if (s.seeds != SeedKind::valleys)
            r.fail(vp, "only used with \"seeds\": \"valleys\"");
        const json& v = j["valleys"];
        r.only(v, vp, {"threshold", "radii"});
        if (v.contains("threshold"))
            s.valleys.threshold = r.in_range(v["threshold"], vp + "/threshold", -10.0, 10.0, false);
        if (v.contains("radii")) {
            if (!v["radii"].is_array() || v["radii"].empty() || v["radii"].size() > 8)
                r.fail(vp + "/radii", "expected an array of 1 to 8 radii (metres)");
            for (std::size_t k = 0; k < v["radii"].size(); ++k)
                s.valleys.radii.push_back(
                    r.in_range(v["radii"][k], vp + "/radii/" + std::to_string(k), 0.0, 1e7, true));
        }
    }
    if (j.contains("min_thickness"))
        s.min_thickness = r.non_negative(j["min_thickness"], p + "/min_thickness");
    if (j.contains("max_thickness"))
        s.max_thickness = r.non_negative(j["max_thickness"], p + "/max_thickness");
    if (s.max_thickness > 0.0 && s.max_thickness <= s.min_thickness)
        r.fail(p + "/max_thickness", "must be 0 (no limit) or larger than min_thickness");
    if (j.contains("profile"))
        s.profile = r.in_range(j["profile"], p + "/profile", 0.0, 1.0, false);
    return s;
}

FlowOptions read_flow(const json& j, const JsonReader& r, const std::string& p, bool& evaporation_given)
{
    r.only(j, p,
           {"wind", "duration", "time_step", "coupling", "inversion_strength", "spread", "max_speed",
            "evaporation_depth", "min_thickness"});
    FlowOptions o;
    if (!j.contains("wind"))
        r.fail(p + "/wind", "missing: the wind [east, north] in m/s");
    o.wind = r.point(j["wind"], p + "/wind");
    if (std::hypot(o.wind.x, o.wind.y) > 100.0)
        r.fail(p + "/wind", "must be at most 100 m/s");
    if (j.contains("duration"))
        o.duration = r.in_range(j["duration"], p + "/duration", 0.0, 2592000.0, false);
    if (j.contains("time_step"))
        o.time_step = r.in_range(j["time_step"], p + "/time_step", 0.0, 86400.0, false);
    if (!(o.time_step > 0.0))
        r.fail(p + "/time_step", "must be > 0 seconds");
    if (o.duration / o.time_step > 1e6)
        r.fail(p + "/time_step", "more than a million steps: take a longer time step (any is stable)");
    if (j.contains("coupling"))
        o.coupling = r.in_range(j["coupling"], p + "/coupling", 0.0, 1.0, false);
    if (j.contains("inversion_strength"))
        o.inversion_strength = r.in_range(j["inversion_strength"], p + "/inversion_strength", 0.0, 50.0, true);
    if (j.contains("spread"))
        o.spread = r.in_range(j["spread"], p + "/spread", 0.0, 1e6, false);
    if (j.contains("max_speed"))
        o.max_speed = r.in_range(j["max_speed"], p + "/max_speed", 0.0, 100.0, true);
    if (j.contains("evaporation_depth")) {
        o.evaporation_depth = r.in_range(j["evaporation_depth"], p + "/evaporation_depth", 0.0, 1e6, false);
        evaporation_given = true;
    }
    if (j.contains("min_thickness"))
        o.min_thickness = r.non_negative(j["min_thickness"], p + "/min_thickness");
    return o;
}

BurnOffOptions read_burn_off(const json& j, const JsonReader& r, const std::string& p, bool& latitude_given)
{
    r.only(j, p, {"time", "day_of_year", "latitude", "burn_rate", "lift_rate", "min_thickness", "step_minutes"});
    BurnOffOptions o;
    if (!j.contains("time"))
        r.fail(p + "/time", "missing: the local solar time (hours) at which to show the fog");
    o.time = r.in_range(j["time"], p + "/time", 0.0, 24.0, false);
    if (j.contains("day_of_year"))
        o.day_of_year = r.integer(j["day_of_year"], p + "/day_of_year", 1, 366);
    if (j.contains("latitude")) {
        o.latitude = r.in_range(j["latitude"], p + "/latitude", -90.0, 90.0, false);
        latitude_given = true;
    }
    if (j.contains("burn_rate"))
        o.burn_rate = r.in_range(j["burn_rate"], p + "/burn_rate", 0.0, 1e5, false);
    if (j.contains("lift_rate"))
        o.lift_rate = r.in_range(j["lift_rate"], p + "/lift_rate", 0.0, 1e5, false);
    if (j.contains("min_thickness"))
        o.min_thickness = r.non_negative(j["min_thickness"], p + "/min_thickness");
    if (j.contains("step_minutes"))
        o.step_minutes = r.in_range(j["step_minutes"], p + "/step_minutes", 0.0, 120.0, false);
    if (!(o.step_minutes > 0.0))
        r.fail(p + "/step_minutes", "must be > 0");
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

std::optional<PlacementSpec> parse_placement(const json& fog, const JsonReader& r, const std::string& p,
                                             const std::filesystem::path& base_dir)
{
    if (!fog.contains("fill")) {
        for (const char* key : {"outline", "flow", "burn_off"})
            if (fog.contains(key))
                r.fail(p + "/" + key, "needs /fog/fill: the fog placed by the terrain that this acts on");
        return std::nullopt;
    }
    for (const char* key : {"mode", "footprint", "altitude", "thickness", "offset", "smoothing", "clearance"})
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
    if (fog.contains("outline")) {
        const json& o = fog["outline"];
        const std::string op = p + "/outline";
        r.only(o, op, {"margin", "tolerance", "min_area"});
        if (o.contains("margin"))
            s.margin = r.in_range(o["margin"], op + "/margin", 0.0, 1e6, false);
        if (o.contains("tolerance"))
            s.tolerance = r.in_range(o["tolerance"], op + "/tolerance", 0.0, 1e6, false);
        if (o.contains("min_area"))
            s.min_area = r.non_negative(o["min_area"], op + "/min_area");
    }
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
        json j;
        j["top"] = g.top;
        switch (g.seeds) {
        case SeedKind::points: j["seeds"] = point_array(g.points); break;
        case SeedKind::all: j["seeds"] = "all"; break;
        case SeedKind::valleys:
            j["seeds"] = "valleys";
            j["valleys"] = {{"threshold", g.valleys.threshold}};
            if (!g.valleys.radii.empty())
                j["valleys"]["radii"] = g.valleys.radii;
            break;
        case SeedKind::mask: j["seeds"] = {{"mask", g.mask_path.string()}}; break;
        }
        j["min_thickness"] = g.min_thickness;
        j["max_thickness"] = g.max_thickness;
        j["profile"] = g.profile;
        regions.push_back(j);
    }
    fog["fill"] = regions.size() == 1 ? regions[0] : regions;
    json outline;
    if (s.margin >= 0.0)
        outline["margin"] = s.margin;
    outline["tolerance"] = s.tolerance;
    outline["min_area"] = s.min_area;
    fog["outline"] = outline;
    if (s.flow) {
        const FlowOptions& o = *s.flow;
        fog["flow"] = {{"wind", {o.wind.x, o.wind.y}},
                       {"duration", o.duration},
                       {"time_step", o.time_step},
                       {"coupling", o.coupling},
                       {"inversion_strength", o.inversion_strength},
                       {"spread", o.spread},
                       {"max_speed", o.max_speed},
                       {"min_thickness", o.min_thickness}};
        if (s.evaporation_given)
            fog["flow"]["evaporation_depth"] = o.evaporation_depth;
    }
    if (s.burn_off) {
        const BurnOffOptions& o = *s.burn_off;
        fog["burn_off"] = {
            {"time", o.time},           {"day_of_year", o.day_of_year},     {"burn_rate", o.burn_rate},
            {"lift_rate", o.lift_rate}, {"min_thickness", o.min_thickness}, {"step_minutes", o.step_minutes}};
        if (s.latitude_given)
            fog["burn_off"]["latitude"] = o.latitude;
    }
}

}  // namespace kiri::geometry
