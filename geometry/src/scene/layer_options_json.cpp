#include "scene/layer_options_json.hpp"

#include "core/json_reader.hpp"

namespace kiri::geometry {

using json = nlohmann::json;

LayerOptions parse_layer_options(const json& j, const std::string& file)
{
    const JsonReader r{file};
    const std::string p = "/layers";
    // detail, detail_scale, dissipation_half_life, wind and time are the medium's now
    // (read_layer_aliases reads them).
    r.only(j, p,
           {"count", "max_count", "spacing_divisor", "narrowing", "enlargement", "enlargement_rate", "opacity",
            "texture_size", "fade_width", "gray", "ground_fade", "detail", "detail_scale", "dissipation_half_life",
            "wind", "time", "shading", "resolution"});
    LayerOptions o;
    if (j.contains("count"))
        o.count = r.integer(j["count"], p + "/count", 1, 1000);
    o.max_count = std::max(o.max_count, o.count);
    if (j.contains("max_count"))
        o.max_count = r.integer(j["max_count"], p + "/max_count", std::max(o.count, 1), 1000);
    if (j.contains("spacing_divisor"))
        o.spacing_divisor = r.positive(j["spacing_divisor"], p + "/spacing_divisor");
    if (j.contains("narrowing"))
        o.narrowing = r.boolean(j["narrowing"], p + "/narrowing");
    if (j.contains("enlargement"))
        o.enlargement = r.boolean(j["enlargement"], p + "/enlargement");
    if (j.contains("enlargement_rate"))
        o.enlargement_rate = r.in_range(j["enlargement_rate"], p + "/enlargement_rate", 0.0, 1.0 / o.max_count, false);
    if (j.contains("opacity"))
        o.opacity = r.in_range(j["opacity"], p + "/opacity", 0.0, 0.999, false);
    if (j.contains("texture_size"))
        o.texture.resolution = r.integer(j["texture_size"], p + "/texture_size", 4, 1024);
    if (j.contains("fade_width"))
        o.texture.fade_width = r.in_range(j["fade_width"], p + "/fade_width", 0.0, 1.0, false);
    if (o.texture.fade_width == 0.0)
        r.fail(p + "/fade_width", "must be > 0");
    if (j.contains("gray"))
        o.texture.gray = r.in_range(j["gray"], p + "/gray", 0.0, 1.0, false);
    if (j.contains("ground_fade"))
        o.ground_fade = r.non_negative(j["ground_fade"], p + "/ground_fade");
    if (j.contains("resolution"))
        o.resolution = r.in_range(j["resolution"], p + "/resolution", 0.125, 1.0, false);
    if (j.contains("shading")) {
        const json& v = j["shading"];
        if (v == "medium")
            o.shading = LayerShading::medium;
        else if (v == "source")
            o.shading = LayerShading::source;
        else
            r.fail(p + "/shading", "expected \"medium\" or \"source\"");
    }
    return o;
}

json layer_options_to_json(const LayerOptions& o)
{
    return {{"count", o.count},
            {"max_count", o.max_count},
            {"spacing_divisor", o.spacing_divisor},
            {"narrowing", o.narrowing},
            {"enlargement", o.enlargement},
            {"enlargement_rate", o.enlargement_rate},
            {"opacity", o.opacity},
            {"texture_size", o.texture.resolution},
            {"fade_width", o.texture.fade_width},
            {"gray", o.texture.gray},
            {"ground_fade", o.ground_fade},
            {"shading", o.shading == LayerShading::medium ? "medium" : "source"},
            {"resolution", o.resolution}};
}

}  // namespace kiri::geometry
