// Camera: the scene's cameras as bookmarks, focus on the fog, reset, orbit or fly, and the
// current view added to the scene as a named camera (saved with it).
#include <imgui.h>
#include <imgui_stdlib.h>

#include "panels/panels.hpp"

namespace kiri::preview {

void camera_panel(const geometry::Scene& scene, UiState& ui)
{
    if (!ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen))
        return;
    for (std::size_t i = 0; i < scene.cameras.size(); ++i) {
        if (i > 0 && ImGui::GetContentRegionAvail().x > 80.0f)
            ImGui::SameLine();
        if (ImGui::Button(scene.cameras[i].name.c_str()))
            ui.bookmark = int(i);
        if (i < 9 && ImGui::IsItemHovered())
            ImGui::SetTooltip("key %zu", i + 1);
    }
    ui.focus_fog |= ImGui::Button("focus on the fog (F)");
    ImGui::SameLine();
    ui.reset_camera |= ImGui::Button("reset (R)");
    ImGui::SameLine();
    ImGui::Checkbox("fly (Tab)", &ui.fly_mode);
    ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.5f);
    ImGui::InputText("##name", &ui.new_camera_name);
    ImGui::SameLine();
    ui.add_camera |= ImGui::Button("add this view");
    ImGui::TextDisabled(ui.fly_mode ? "left drag: look around; right: pan; wheel: zoom"
                                    : "left drag: orbit; right: pan; wheel: zoom");
    ImGui::TextDisabled("WASD, Q/E: fly (Shift faster); double-click: orbit there");
}

}  // namespace kiri::preview
