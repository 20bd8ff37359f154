#include "scene/medium_options_json.hpp"

#include <vector>

#include "scene/field_json.hpp"

namespace kiri::geometry {

using json = nlohmann::json;

namespace {

// The medium's motion, which the "layers" section gave before the medium owned it.
std::vector<FieldInfo> moved_from_layers()
{
    MediumOptions m;
    return {field_of(m, m.detail), field_of(m, m.detail_scale), field_of(m, m.wind), field_of(m, m.time),
            field_of(m, m.dissipation_half_life)};
}

}  // namespace

MediumOptions parse_medium_options(const json& j, const std::string& file)
{
    const JsonReader r{file};
    const std::string p = "/medium";
    MediumOptions o;
    read_fields(r, j, p, o);
    // Three ways to give the extinction.
    const FieldInfo extinction = field_of(o, o.extinction), visibility = field_named(o, "visibility"),
                    water = field_named(o, "liquid_water_content"), radius = field_named(o, "droplet_radius");
    const auto given = [&](const FieldInfo& f) { return j.contains(std::string(f.key)); };
    if (int(given(extinction)) + int(given(visibility)) + int(given(water)) > 1)
        r.fail(p, "give only one of extinction, visibility and liquid_water_content (each sets the extinction)");
    if (given(radius) && !given(water))
        r.fail(p + "/droplet_radius", "only used with liquid_water_content");
    const auto value = [&](const FieldInfo& f) {
        double v = 0.0;
        read_value(r, j[std::string(f.key)], p + "/" + std::string(f.key), f, v);
        return v;
    };
    if (given(visibility))
        o.extinction = extinction_from_visibility(value(visibility));
    if (given(water))
        o.extinction = extinction_from_liquid_water(value(water), given(radius) ? value(radius) : 7.0);
    if (o.extinction > 1e3)  // a visibility of 4 mm: no fog is that dense, and the renderers' steps lose it
        r.fail(p, "extinction above 1000 1/m (visibility under 4 mm)");
    return o;
}

std::set<std::string> medium_keys_in_layers()
{
    std::set<std::string> keys;
    for (const FieldInfo& f : moved_from_layers())
        keys.insert(std::string(f.key));
    return keys;
}

void read_layer_aliases(const json& layers, const json* medium, const std::string& file, MediumOptions& o)
{
    const JsonReader r{file};
    json given = json::object();
    for (const FieldInfo& f : moved_from_layers()) {
        const std::string key(f.key);
        if (!layers.contains(key))
            continue;
        if (medium && medium->contains(key))
            r.fail("/layers/" + key, "the old name of /medium/" + key + ", which the scene gives too: give only that");
        given[key] = layers[key];
    }
    const std::string section = "/layers";
    visit_fields(o, FieldReader{r, given, section, {}});
}

json medium_options_to_json(const MediumOptions& o) { return write_fields(o); }

}  // namespace kiri::geometry
