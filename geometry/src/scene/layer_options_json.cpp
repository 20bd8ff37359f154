#include "scene/layer_options_json.hpp"

#include <algorithm>

#include "scene/field_json.hpp"

namespace kiri::geometry {

using json = nlohmann::json;

LayerOptions parse_layer_options(const json& j, const std::string& file, const std::set<std::string>& medium_keys)
{
    const JsonReader r{file};
    LayerOptions o;
    read_fields(r, j, "/layers", o, medium_keys);
    o.max_count = std::max(o.max_count, o.count);  // a count above the default's most layers raises it
    return o;
}

json layer_options_to_json(const LayerOptions& o) { return write_fields(o); }

}  // namespace kiri::geometry
