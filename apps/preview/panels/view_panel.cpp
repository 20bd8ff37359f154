// What is drawn: the fog layers, the fitted surface (shaded or as a colour map), its
// wireframes, and the resolution the 3D view is drawn at.
#include <cstdio>

#include <imgui.h>

#include "panels/panels.hpp"
#include "panels/widgets.hpp"

namespace kiri::preview {

render::FogMode next_fog_mode(render::FogMode mode)
{
    return mode == render::FogMode::combined ? render::FogMode::layers : render::FogMode(int(mode) + 1);
}

bool view_panel(ViewOptions& view, const FogViews* views)
{
    if (!ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen))
        return false;
    bool changed = ImGui::Checkbox("fog", &view.fog);
    ImGui::SameLine();
    // The combo lists the fog's modes, from layers (FogMode 1) on.
    int mode = int(view.mode) - int(render::FogMode::layers);
    ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.5f);
    changed |= ImGui::Combo("render mode (M)", &mode, "layers\0particles\0froxel\0combined\0");
    view.mode = render::FogMode(mode + int(render::FogMode::layers));
    int surface = int(view.surface);
    changed |= ImGui::Combo("base surface", &surface,
                            "hidden\0shaded\0deviation from the fit's target\0height above the terrain\0");
    view.surface = ViewOptions::Surface(surface);
    if (view.surface != ViewOptions::Surface::hidden)
        changed |= ImGui::SliderFloat("opacity", &view.surface_opacity, 0.05f, 1.0f, "%.2f");
    char low[64], high[64];
    if (views && view.surface == ViewOptions::Surface::deviation) {
        std::snprintf(low, sizeof low, "-%.1f m (below the target)", views->deviation_range);
        std::snprintf(high, sizeof high, "+%.1f m", views->deviation_range);
        color_legend(low, high, true);
    } else if (views && view.surface == ViewOptions::Surface::clearance) {
        std::snprintf(high, sizeof high, "%.0f m", views->clearance_range);
        color_legend("0 m", high, false);
    }
    ImGui::TextUnformatted("wireframe:");
    ImGui::SameLine();
    changed |= ImGui::Checkbox("triangles", &view.tessellation);
    ImGui::SameLine();
    changed |= ImGui::Checkbox("patches", &view.patches);
    ImGui::SameLine();
    changed |= ImGui::Checkbox("control mesh", &view.control_mesh);
    changed |= ImGui::SliderFloat("resolution", &view.render_scale, 0.25f, 1.0f, "%.2f");
    changed |= ImGui::Checkbox("lower while moving", &view.reduce_while_moving);
    if (view.reduce_while_moving) {
        ImGui::SameLine();
        ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.4f);
        changed |= ImGui::SliderFloat("##moving", &view.moving_fps, 1.0f, 60.0f, "%.0f frames/s");
    }
    return changed;
}

}  // namespace kiri::preview
