// Terrain: the raster and how its values become heights. Any change reloads the terrain (and
// refits the fog over it) on the worker thread.
#include <imgui.h>

#include "panels/panels.hpp"
#include "panels/widgets.hpp"

namespace kiri::preview {

bool terrain_panel(geometry::Scene& scene)
{
    if (!ImGui::CollapsingHeader("Terrain", ImGuiTreeNodeFlags_DefaultOpen))
        return false;
    geometry::TerrainSpec& t = scene.terrain;
    ImGui::TextWrapped("%s", t.path.filename().string().c_str());
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("%s", t.path.string().c_str());
    bool changed = edit("exaggeration", t, t.exaggeration, "%.2f");
    if (ImGui::TreeNode("raster units")) {
        changed |= edit("vertical scale", t, t.vertical_scale, "%.3f m/unit");
        changed |= field_drag("vertical offset (m)", t.vertical_offset, geometry::field_of(t, t.vertical_offset), 1.0);
        changed |= edit("cell size (m)", t, t.cell_size, t.cell_size > 0.0 ? "%.2f" : "from the raster");
        ImGui::TreePop();
    }
    return changed;
}

}  // namespace kiri::preview
