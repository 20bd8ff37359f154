// The fog's layer stack ([Thesis] (2.6)-(2.10), docs/layers.md): most options apply on the next frame;
// the texture options reshape the layer base (recomputed on the worker). Ranges and tooltips
// are the layers' field list's (layer_stack.hpp).
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
    bool changed = edit("layers", o, o.count);
    o.max_count = std::max(o.max_count, o.count);
    changed |= edit("spacing rule (2.8, 2.9)", o, o.narrowing);
    // The source's shading alone: the medium's takes the medium's optics and is not enlarged
    // (geometry::layers_enlarge).
    const bool source = o.shading == geometry::LayerShading::source;
    if (source) {
        ImGui::SameLine();
        changed |= edit("scale rule (2.10)", o, o.enlargement);
        changed |= edit("opacity", o, o.opacity, "%.3f");
    }
    changed |= edit("ground fade (m)", o, o.ground_fade, "%.0f");
    if (ImGui::TreeNode("more")) {
        changed |= edit("spacing divisor (2.6)", o, o.spacing_divisor, "%.0f");
        changed |= edit("most layers", o, o.max_count);
        if (source)
            changed |= edit("enlargement rate (2.10)", o, o.enlargement_rate, "%.5f");
        changed |= edit("texture fade width", o, o.texture.fade_width, "%.2f");
        changed |= edit("texture gray", o, o.texture.gray, "%.2f");
        changed |= edit("texture size", o, o.texture.resolution);
        changed |= edit("layer pass resolution", o, o.resolution, "%.3f");
        ImGui::TreePop();
    }
    return changed;
}

}  // namespace kiri::preview
