#include "kiri/geometry/scene/scene_fields.hpp"

#include <functional>
#include <stdexcept>
#include <utility>

#include "kiri/geometry/scene/scene.hpp"
#include "scene/field_docs.hpp"

namespace kiri::geometry {
namespace {

using Table = std::function<std::string()>;

const std::vector<std::pair<std::string, Table>>& tables()
{
    static const std::vector<std::pair<std::string, Table>> all = {
        {"terrain", [] { return markdown_table<TerrainSpec>(); }},
        {"cameras", [] { return markdown_table<CameraSpec>(); }},
        {"sun", [] { return markdown_table<SunSpec>(); }},
        {"image", [] { return markdown_table<ImageSpec>(); }},
        {"fog", [] { return markdown_table<FogSpec>(); }},
        {"fog/tessellation", [] { return markdown_table<TessellationOptions>(); }},
        {"fog/fill", [] { return markdown_table<FillRegionSpec>(); }},
        {"fog/fill/valleys", [] { return markdown_table<ValleyOptions>(); }},
        {"fog/outline", [] { return markdown_table<PlacementSpec>(OutlineFields{}); }},
        {"fog/flow", [] { return markdown_table<FlowOptions>(); }},
        {"fog/burn_off", [] { return markdown_table<BurnOffOptions>(); }},
        {"layers", [] { return markdown_table<LayerOptions>(); }},
        {"medium", [] { return markdown_table<MediumOptions>(); }},
        {"particles", [] { return markdown_table<ParticleOptions>(); }},
        {"froxel", [] { return markdown_table<FroxelOptions>(); }},
        {"froxel/height_fog", [] { return markdown_table<HeightFog>(); }},
        {"combined", [] { return markdown_table<FogPartition>(); }},
    };
    return all;
}

}  // namespace

std::vector<std::string> documented_sections()
{
    std::vector<std::string> names;
    for (const auto& [name, table] : tables())
        names.push_back(name);
    return names;
}

std::string fields_table(std::string_view section)
{
    for (const auto& [name, table] : tables())
        if (name == section)
            return table();
    throw std::invalid_argument("no field list for the section \"" + std::string(section) + "\"");
}

}  // namespace kiri::geometry
