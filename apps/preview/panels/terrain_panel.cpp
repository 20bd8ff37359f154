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
    bool changed = slider("exaggeration", t.exaggeration, 0.1, 10.0, "%.2f", true);
    if (ImGui::TreeNode("raster units")) {
        changed |= slider("vertical scale", t.vertical_scale, 1e-3, 1e3, "%.3f m/unit", true);
        changed |= drag("vertical offset (m)", t.vertical_offset, 1.0);
        changed |= slider("cell size (m)", t.cell_size, 0.0, 1000.0, t.cell_size > 0.0 ? "%.2f" : "from the raster");
        ImGui::TreePop();
    }
    return changed;
}

}  // namespace kiri::preview
