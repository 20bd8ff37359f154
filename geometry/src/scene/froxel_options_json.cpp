#include "scene/froxel_options_json.hpp"

#include "kiri/geometry/medium/medium.hpp"
#include "scene/field_json.hpp"

namespace kiri::geometry {

using json = nlohmann::json;

namespace {

HeightFog parse_height_fog(const json& j, const JsonReader& r, const std::string& p)
{
    HeightFog f;
    read_fields(r, j, p, f);
    const FieldInfo visibility = field_named(f, "visibility");
    if (const std::string key(visibility.key); j.contains(key)) {
        if (j.contains(std::string(field_of(f, f.extinction).key)))
            r.fail(p, "give only one of extinction and visibility");
        double v = 0.0;
        read_value(r, j[key], p + "/" + key, visibility, v);
        f.extinction = extinction_from_visibility(v);
    }
    return f;
}

}  // namespace

FroxelOptions parse_froxel_options(const json& j, const std::string& file)
{
    const JsonReader r{file};
    const std::string p = "/froxel";
    FroxelOptions o;
    read_fields(r, j, p, o);
    if (const std::string key(field_named(o, "height_fog").key); j.contains(key))
        o.height_fog = parse_height_fog(j[key], r, p + "/" + key);
    validate_froxel_options(o, file);
    return o;
}

json froxel_options_to_json(const FroxelOptions& o)
{
    json j = write_fields(o);
    j[std::string(field_named(o, "height_fog").key)] = write_fields(o.height_fog);
    return j;
}

}  // namespace kiri::geometry
