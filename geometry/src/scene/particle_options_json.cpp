#include "scene/particle_options_json.hpp"

#include "core/json_reader.hpp"

namespace kiri::geometry {

using json = nlohmann::json;

namespace {

const char* frame_name(LightFrame f)
{
    switch (f) {
    case LightFrame::light: return "light";
    case LightFrame::sheared: return "sheared";
    default: return "auto";
    }
}

}  // namespace

ParticleOptions parse_particle_options(const json& j, const std::string& file)
{
    const JsonReader r{file};
    const std::string p = "/particles";
    r.only(j, p,
           {"count", "spacing", "radius_scale", "radius", "albedo", "extinction", "forward_scattering", "seed",
            "candidates", "resolution", "format", "frame", "soft_edge"});
    if (j.contains("count") && j.contains("spacing"))
        r.fail(p, "give count or spacing, not both (each sets the number of particles)");
    ParticleOptions o;
    if (j.contains("count"))
        o.count = r.integer(j["count"], p + "/count", 1, 2000000);
    if (j.contains("spacing"))
        o.spacing = r.positive(j["spacing"], p + "/spacing");
    if (j.contains("radius_scale"))
        o.radius_scale = r.in_range(j["radius_scale"], p + "/radius_scale", 0.0, 100.0, true);
    if (j.contains("radius")) {
        const json& range = j["radius"];
        if (!range.is_array() || range.size() != 2)
            r.fail(p + "/radius", "expected [min, max] in metres");
        o.radius_min = r.positive(range[0], p + "/radius/0");
        o.radius_max = r.positive(range[1], p + "/radius/1");
        if (o.radius_min > o.radius_max)
            r.fail(p + "/radius", "the minimum is above the maximum");
    }
    if (j.contains("albedo"))
        o.albedo = r.in_range(j["albedo"], p + "/albedo", 0.0, 1.0, false);
    if (j.contains("extinction"))
        o.extinction = r.in_range(j["extinction"], p + "/extinction", 0.0, 1000.0, false);
    if (j.contains("forward_scattering"))
        o.forward_scattering = r.in_range(j["forward_scattering"], p + "/forward_scattering", 0.0, 1.0, false);
    if (j.contains("seed"))
        o.seed = std::uint64_t(r.integer(j["seed"], p + "/seed", 0, 2147483647));
    if (j.contains("candidates"))
        o.candidates = r.in_range(j["candidates"], p + "/candidates", 1.0, 50.0, false);
    if (j.contains("resolution"))
        o.resolution = r.integer(j["resolution"], p + "/resolution", 16, 512);
    if (j.contains("format")) {
        const std::string f = r.string(j["format"], p + "/format");
        if (f != "r16f" && f != "r32f")
            r.fail(p + "/format", "expected \"r16f\" or \"r32f\", got \"" + f + "\"");
        o.half_float = f == "r16f";
    }
    if (j.contains("frame")) {
        const std::string f = r.string(j["frame"], p + "/frame");
        if (f == "auto")
            o.frame = LightFrame::automatic;
        else if (f == "light")
            o.frame = LightFrame::light;
        else if (f == "sheared")
            o.frame = LightFrame::sheared;
        else
            r.fail(p + "/frame", "expected \"auto\", \"light\" or \"sheared\", got \"" + f + "\"");
    }
    if (j.contains("soft_edge"))
        o.soft_edge = r.non_negative(j["soft_edge"], p + "/soft_edge");
    validate_particle_options(o, file);
    return o;
}

json particle_options_to_json(const ParticleOptions& o)
{
    json j = {{"radius_scale", o.radius_scale},
              {"seed", o.seed},
              {"candidates", o.candidates},
              {"resolution", o.resolution},
              {"format", o.half_float ? "r16f" : "r32f"},
              {"frame", frame_name(o.frame)},
              {"soft_edge", o.soft_edge}};
    if (o.spacing > 0.0)
        j["spacing"] = o.spacing;
    else
        j["count"] = o.count;
    if (o.radius_min > 0.0 && o.radius_max > 0.0)
        j["radius"] = {o.radius_min, o.radius_max};
    if (o.albedo >= 0.0)
        j["albedo"] = o.albedo;
    if (o.extinction > 0.0)
        j["extinction"] = o.extinction;
    if (o.forward_scattering >= 0.0)
        j["forward_scattering"] = o.forward_scattering;
    return j;
}

}  // namespace kiri::geometry
