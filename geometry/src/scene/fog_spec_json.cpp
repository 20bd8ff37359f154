#include "scene/fog_spec_json.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "kiri/geometry/core/error.hpp"
#include "scene/field_json.hpp"
#include "scene/placement_json.hpp"

namespace kiri::geometry {
namespace {

using json = nlohmann::json;

void read_footprint(const json& f, const JsonReader& r, const std::string& fp, FogSpec& s)
{
    if (!f.is_object() || !f.contains("type") || !f["type"].is_string())
        r.fail(fp, "expected an object with \"type\": \"terrain\", \"rectangle\" or \"polygon\"");
    const std::string type = f["type"];
    if (type == "terrain") {
        read_fields(r, f, fp, s, {"type"}, {}, TerrainFootprintFields{});
    } else if (type == "rectangle") {
        r.only(f, fp, {"type", "min", "max"});
        if (!f.contains("min") || !f.contains("max"))
            r.fail(fp, "a rectangle needs \"min\" and \"max\"");
        const glm::dvec2 lo = r.point(f["min"], fp + "/min"), hi = r.point(f["max"], fp + "/max");
        if (!(lo.x < hi.x && lo.y < hi.y))
            r.fail(fp + "/max", "must be greater than min in x and y");
        s.footprint = rectangle_footprint(lo, hi);
    } else if (type == "polygon") {
        r.only(f, fp, {"type", "points"});
        if (!f.contains("points") || !f["points"].is_array())
            r.fail(fp + "/points", "expected an array of [x, y] points");
        for (std::size_t k = 0; k < f["points"].size(); ++k)
            s.footprint.polygon.push_back(r.point(f["points"][k], fp + "/points/" + std::to_string(k)));
        try {
            validate_footprint(s.footprint);
        } catch (const InputError& e) {
            r.fail(fp + "/points", e.reason());
        }
    } else {
        r.fail(fp + "/type", "expected \"terrain\", \"rectangle\" or \"polygon\", got \"" + type + "\"");
    }
}

json footprint_json(const FogSpec& s)
{
    if (!s.footprint.polygon.empty()) {
        json pts = json::array();
        for (const auto& q : s.footprint.polygon)
            pts.push_back({q.x, q.y});
        return {{"type", "polygon"}, {"points", pts}};
    }
    json j = write_fields(s, TerrainFootprintFields{});
    j["type"] = "terrain";
    return j;
}

}  // namespace

FogSpec parse_fog_spec(const json& j, const std::string& file, const std::string& p,
                       const std::filesystem::path& base_dir)
{
    const JsonReader r{file};
    FogSpec s;
    read_fields(r, j, p, s);
    s.placement = parse_placement(j, r, p, base_dir);
    if (s.placement)
        s.fit.mode = FitMode::lake;  // a flat top (or the placed top) over the terrain
    if (j.contains("footprint"))
        read_footprint(j["footprint"], r, p + "/footprint", s);
    const std::string altitude(field_of(s, s.fit.altitude).key);
    if (s.fit.mode == FitMode::lake && !s.placement && !j.contains(altitude))
        r.fail(p + "/" + altitude, "lake mode needs the altitude of the fog top (metres)");
    if (s.fit.mode == FitMode::blanket && s.fit.clearance > s.fit.thickness)
        r.fail(p + "/" + std::string(field_of(s, s.fit.clearance).key),
               "clearance " + std::to_string(s.fit.clearance) + " m is larger than the fog thickness " +
                   std::to_string(s.fit.thickness) + " m");
    if (j.contains("tessellation"))
        read_fields(r, j["tessellation"], p + "/tessellation", s.tessellation);
    return s;
}

json fog_spec_to_json(const FogSpec& s)
{
    json j = write_fields(s);
    j["tessellation"] = write_fields(s.tessellation);
    if (!s.placement) {
        j["footprint"] = footprint_json(s);
        return j;
    }
    // The footprint, mode and lake target come from the terrain.
    for (const std::string& key : keys_set_by_fill())
        j.erase(key);
    placement_to_json(*s.placement, j);
    return j;
}

}  // namespace kiri::geometry
