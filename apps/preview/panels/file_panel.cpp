// Saving the edited scene (JSON that loads back) and screenshots (PNG), and the last message.
#include <imgui.h>
#include <imgui_stdlib.h>

#include "panels/panels.hpp"

namespace kiri::preview {

void file_panel(UiState& ui)
{
    if (ImGui::CollapsingHeader("File", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::InputText("scene file", &ui.save_path);
        ui.save |= ImGui::Button("save (Ctrl+S)");
        ImGui::SameLine();
        ui.screenshot |= ImGui::Button("screenshot (F12, P)");
        ImGui::SameLine();
        ImGui::Checkbox("timings (T)", &ui.view.show_stats);
        ImGui::TextDisabled("H hides this panel");
    }
    if (!ui.message.empty()) {
        if (ui.message_is_error)
            ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.45f, 0.4f, 1.0f));
        ImGui::TextWrapped("%s", ui.message.c_str());
        if (ui.message_is_error)
            ImGui::PopStyleColor();
    }
}

}  // namespace kiri::preview
