#include "scene/fog_partition_json.hpp"

#include <algorithm>

#include "core/json_reader.hpp"

namespace kiri::geometry {

using json = nlohmann::json;

FogPartition parse_fog_partition(const json& j, const std::string& file)
{
    const JsonReader r{file};
    const std::string p = "/combined";
    r.only(j, p, {"near_start", "near_end", "particle_share", "particle_band"});
    FogPartition o;
    if (j.contains("near_start"))
        o.near_start = r.in_range(j["near_start"], p + "/near_start", 0.0, 1e7, false);
    if (j.contains("near_end"))
        o.near_end = r.in_range(j["near_end"], p + "/near_end", 0.0, 1e7, false);
    if (j.contains("near_start") && !j.contains("near_end"))
        o.near_end = std::max(o.near_end, o.near_start);
    if (o.near_end < o.near_start)
        r.fail(p + "/near_end", "must be >= near_start");
    if (j.contains("particle_share"))
        o.particle_share = r.in_range(j["particle_share"], p + "/particle_share", 0.0, 1.0, false);
    if (j.contains("particle_band"))
        o.particle_band = r.in_range(j["particle_band"], p + "/particle_band", 0.0, 1.0, false);
    if (!(o.particle_band > 0.0))
        r.fail(p + "/particle_band", "must be > 0");
    validate_fog_partition(o, file);
    return o;
}

json fog_partition_to_json(const FogPartition& o)
{
    return {{"near_start", o.near_start},
            {"near_end", o.near_end},
            {"particle_share", o.particle_share},
            {"particle_band", o.particle_band}};
}

}  // namespace kiri::geometry
