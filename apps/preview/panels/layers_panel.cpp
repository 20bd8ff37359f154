// The fog's layer stack (REFERENCE 1.3, docs/layers.md): most options apply on the next frame;
// the texture options reshape the layer base (recomputed on the worker).
#include <algorithm>

#include <imgui.h>

#include "panels/panels.hpp"
#include "panels/widgets.hpp"

namespace kiri::preview {

bool layers_panel(geometry::Scene& scene)
{
    if (!ImGui::CollapsingHeader("Layers", ImGuiTreeNodeFlags_DefaultOpen))
        return false;
    geometry::LayerOptions& o = scene.layers;
    bool changed = slider("layers", o.count, 1, 100);
    o.max_count = std::max(o.max_count, o.count);
    changed |= ImGui::Checkbox("spacing rule (2.8, 2.9)", &o.narrowing);
    ImGui::SameLine();
    changed |= ImGui::Checkbox("scale rule (2.10)", &o.enlargement);
    if (o.shading == geometry::LayerShading::source)  // the medium's shading takes the medium's optics
        changed |= slider("opacity", o.opacity, 0.0, 0.9, "%.3f");
    changed |= slider("ground fade (m)", o.ground_fade, 0.0, 200.0, "%.0f");
    if (ImGui::TreeNode("more")) {
        changed |= slider("spacing divisor (2.6)", o.spacing_divisor, 20.0, 2000.0, "%.0f", true);
        changed |= slider("most layers", o.max_count, o.count, 400);
        // (2.10) must keep every layer's scale below 2: rate * max_count < 1.
        changed |= slider("enlargement rate (2.10)", o.enlargement_rate, 0.0, 0.999 / o.max_count, "%.5f");
        changed |= slider("texture fade width", o.texture.fade_width, 0.02, 1.0, "%.2f");
        changed |= slider("texture gray", o.texture.gray, 0.0, 1.0, "%.2f");
        changed |= slider("texture size", o.texture.resolution, 4, 1024);
        changed |= slider("layer pass resolution", o.resolution, 0.125, 1.0, "%.3f");
        ImGui::TreePop();
    }
    return changed;
}

}  // namespace kiri::preview
