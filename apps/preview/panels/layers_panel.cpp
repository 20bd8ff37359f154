// The fog's layer stack ([Thesis] (2.6)-(2.10), docs/layers.md): most options apply on the next frame;
// the texture options reshape the layer base (recomputed on the worker).
#include <algorithm>

#include <glm/vec2.hpp>
#include <imgui.h>

#include "panels/panels.hpp"
#include "panels/widgets.hpp"

namespace kiri::preview {

bool layers_panel(geometry::Scene& scene, ViewOptions& view)
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
    changed |= slider("detail", o.detail, 0.0, 1.0, "%.2f");
    changed |= slider("detail scale (m)", o.detail_scale, 100.0, 10000.0, "%.0f", true);
    changed |= slider("ground fade (m)", o.ground_fade, 0.0, 200.0, "%.0f");
    float wind[2] = {float(o.wind.x), float(o.wind.y)};
    if (ImGui::SliderFloat2("wind (m/s)", wind, -30.0f, 30.0f, "%.1f")) {
        o.wind = {wind[0], wind[1]};
        changed = true;
    }
    changed |= slider("dissipation half-life (s)", o.dissipation_half_life, 0.0, 3600.0, "%.0f");
    changed |= slider("time (s)", o.time, 0.0, 3600.0, "%.0f");
    ImGui::SameLine();
    changed |= ImGui::Checkbox("play", &view.play_time);
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
