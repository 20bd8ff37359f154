#include "scene/fog_partition_json.hpp"

#include <algorithm>

#include "scene/field_json.hpp"

namespace kiri::geometry {

using json = nlohmann::json;

FogPartition parse_fog_partition(const json& j, const std::string& file)
{
    const JsonReader r{file};
    FogPartition o;
    // One end given alone moves the other: a hand-over 4 times as far as it starts.
    const bool start = j.is_object() && j.contains("near_start"), end = j.is_object() && j.contains("near_end");
    if (end && !start)
        o.near_start = 0.0;  // near_end is read against it: set below
    read_fields(r, j, "/combined", o);
    if (start && !end)
        o.near_end = std::min(std::max(4.0 * o.near_start, o.near_start), fog_partition_everywhere);
    if (end && !start)
        o.near_start = 0.25 * o.near_end;
    validate_fog_partition(o, file);
    return o;
}

json fog_partition_to_json(const FogPartition& o) { return write_fields(o); }

}  // namespace kiri::geometry
