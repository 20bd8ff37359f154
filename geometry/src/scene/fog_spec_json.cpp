#include "scene/fog_spec_json.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "kiri/geometry/core/error.hpp"
#include "scene/placement_json.hpp"
#include "core/json_reader.hpp"

namespace kiri::geometry {
namespace {

using json = nlohmann::json;

using Reader = JsonReader;

}  // namespace

FogSpec parse_fog_spec(const json& j, const std::string& file, const std::string& p,
                       const std::filesystem::path& base_dir)
{
    const Reader r{file};
    r.only(j, p,
           {"footprint", "surface", "patch_size", "mode", "offset", "smoothing", "altitude", "clearance", "thickness",
            "smoothness", "samples_per_patch", "tessellation", "fill", "outline", "flow", "burn_off"});
    FogSpec s;
    s.placement = parse_placement(j, r, p, base_dir);
    if (s.placement)
        s.fit.mode = FitMode::lake;  // a flat top (or the placed top) over the terrain
    if (j.contains("footprint")) {
        const json& f = j["footprint"];
        const std::string fp = p + "/footprint";
        if (!f.is_object() || !f.contains("type") || !f["type"].is_string())
            r.fail(fp, "expected an object with \"type\": \"terrain\", \"rectangle\" or \"polygon\"");
        const std::string type = f["type"];
        if (type == "terrain") {
            r.only(f, fp, {"type", "margin"});
            if (f.contains("margin"))
                s.margin = r.non_negative(f["margin"], fp + "/margin");
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
    if (j.contains("surface")) {
        const json& v = j["surface"];
        if (v == "gregory")
            s.surface = SurfaceKind::gregory;
        else if (v == "catmull-clark")
            s.surface = SurfaceKind::catmull_clark;
        else
            r.fail(p + "/surface", "expected \"gregory\" or \"catmull-clark\"");
    }
    if (j.contains("patch_size"))
        s.patch_size = r.positive(j["patch_size"], p + "/patch_size");
    if (j.contains("mode")) {
        const json& v = j["mode"];
        if (v == "blanket")
            s.fit.mode = FitMode::blanket;
        else if (v == "lake")
            s.fit.mode = FitMode::lake;
        else
            r.fail(p + "/mode", "expected \"blanket\" or \"lake\"");
    }
    if (j.contains("offset"))
        s.fit.offset = r.number(j["offset"], p + "/offset");
    if (j.contains("smoothing"))
        s.fit.smoothing_length = r.non_negative(j["smoothing"], p + "/smoothing");
    if (j.contains("altitude"))
        s.fit.altitude = r.number(j["altitude"], p + "/altitude");
    else if (s.fit.mode == FitMode::lake && !s.placement)
        r.fail(p + "/altitude", "lake mode needs the altitude of the fog top (metres)");
    if (j.contains("clearance"))
        s.fit.clearance = r.non_negative(j["clearance"], p + "/clearance");
    if (j.contains("thickness"))
        s.fit.thickness = r.positive(j["thickness"], p + "/thickness");
    if (s.fit.mode == FitMode::blanket && s.fit.clearance > s.fit.thickness)
        r.fail(p + "/clearance",
               "clearance " + std::to_string(s.fit.clearance) + " m is larger than the fog thickness " +
                   std::to_string(s.fit.thickness) + " m");
    if (j.contains("smoothness"))
        s.fit.smoothness = r.non_negative(j["smoothness"], p + "/smoothness");
    if (j.contains("samples_per_patch"))
        s.fit.samples_per_patch = r.integer(j["samples_per_patch"], p + "/samples_per_patch", 1, 1024);
    if (j.contains("tessellation")) {
        const json& t = j["tessellation"];
        const std::string tp = p + "/tessellation";
        r.only(t, tp, {"level", "tolerance", "max_level"});
        if (t.contains("level"))
            s.tessellation.level = r.integer(t["level"], tp + "/level", 1, 256);
        if (t.contains("tolerance"))
            s.tessellation.tolerance = r.positive(t["tolerance"], tp + "/tolerance");
        if (t.contains("max_level"))
            s.tessellation.max_level = r.integer(t["max_level"], tp + "/max_level", 1, 256);
    }
    return s;
}

json fog_spec_to_json(const FogSpec& s)
{
    json j;
    if (s.placement) {
        // The footprint, mode and lake target come from the terrain.
        placement_to_json(*s.placement, j);
        j["surface"] = to_string(s.surface);
        j["patch_size"] = s.patch_size;
        j["smoothness"] = s.fit.smoothness;
        if (s.fit.samples_per_patch > 0)
            j["samples_per_patch"] = s.fit.samples_per_patch;
        j["tessellation"] = {{"level", s.tessellation.level}, {"max_level", s.tessellation.max_level}};
        if (s.tessellation.tolerance > 0.0)
            j["tessellation"]["tolerance"] = s.tessellation.tolerance;
        return j;
    }
    if (s.footprint.polygon.empty()) {
        j["footprint"] = {{"type", "terrain"}, {"margin", s.margin}};
    } else {
        json pts = json::array();
        for (const auto& q : s.footprint.polygon)
            pts.push_back({q.x, q.y});
        j["footprint"] = {{"type", "polygon"}, {"points", pts}};
    }
    j["surface"] = to_string(s.surface);
    j["patch_size"] = s.patch_size;
    j["mode"] = to_string(s.fit.mode);
    j["offset"] = s.fit.offset;
    j["smoothing"] = s.fit.smoothing_length;
    j["altitude"] = s.fit.altitude;
    j["clearance"] = s.fit.clearance;
    j["thickness"] = s.fit.thickness;
    j["smoothness"] = s.fit.smoothness;
    if (s.fit.samples_per_patch > 0)  // 0 = automatic, which the reader expresses by omission
        j["samples_per_patch"] = s.fit.samples_per_patch;
    j["tessellation"] = {{"level", s.tessellation.level}, {"max_level", s.tessellation.max_level}};
    if (s.tessellation.tolerance > 0.0)
        j["tessellation"]["tolerance"] = s.tessellation.tolerance;
    return j;
}

}  // namespace kiri::geometry
