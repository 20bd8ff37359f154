#include "scene/fog_partition_json.hpp"

#include <algorithm>

#include "scene/field_json.hpp"

namespace kiri::geometry {

using json = nlohmann::json;

FogPartition parse_fog_partition(const json& j, const std::string& file)
{
    const JsonReader r{file};
    FogPartition o;
    read_fields(r, j, "/combined", o);
    o.near_end = std::max(o.near_end, o.near_start);  // a start beyond the default's end moves the end
    validate_fog_partition(o, file);
    return o;
}

json fog_partition_to_json(const FogPartition& o) { return write_fields(o); }

}  // namespace kiri::geometry
