// The fog's optics and motion (the scene's "medium" section, docs/medium.md): shared by every
// renderer, so an edit here applies to the layers on the next frame (and to the volume
// renderers). Playing the time drifts and dissipates the fog in real time.
#include <cmath>

#include <imgui.h>

#include "kiri/geometry/medium/medium.hpp"
#include "panels/panels.hpp"
#include "panels/widgets.hpp"

namespace kiri::preview {

bool medium_panel(geometry::Scene& scene, ViewOptions& view)
{
    if (!ImGui::CollapsingHeader("Medium", ImGuiTreeNodeFlags_DefaultOpen))
        return false;
    geometry::MediumOptions& o = scene.medium;
    bool changed = false;
    // Visibility is what people know of fog (Koschmieder); the extinction follows.
    double visibility = geometry::visibility_from_extinction(o.extinction);
    if (slider("visibility (m)", visibility, 10.0, 20000.0, "%.0f", true)) {
        o.extinction = geometry::extinction_from_visibility(visibility);
        changed = true;
    }
    ImGui::TextDisabled("extinction %.4f 1/m", o.extinction);
    changed |= slider("albedo", o.albedo, 0.0, 1.0, "%.3f");
    changed |= slider("anisotropy g", o.anisotropy, -0.95, 0.95, "%.2f");
    changed |= slider("top density", o.top_density, 0.0, 1.0, "%.2f");
    changed |= slider("scattering octaves", o.scattering_octaves, 1, 8);
    changed |= slider("detail", o.detail, 0.0, 1.0, "%.2f");
    changed |= slider("detail scale (m)", o.detail_scale, 100.0, 10000.0, "%.0f", true);
    float wind[2] = {float(o.wind.x), float(o.wind.y)};
    if (ImGui::SliderFloat2("wind (m/s)", wind, -30.0f, 30.0f, "%.1f")) {
        o.wind = {wind[0], wind[1]};
        changed = true;
    }
    changed |= slider("dissipation half-life (s)", o.dissipation_half_life, 0.0, 3600.0, "%.0f");
    changed |= slider("time (s)", o.time, 0.0, 3600.0, "%.0f");
    ImGui::SameLine();
    changed |= ImGui::Checkbox("play", &view.play_time);
    bool medium = scene.layers.shading == geometry::LayerShading::medium;
    if (ImGui::Checkbox("layers shaded from the medium", &medium)) {
        scene.layers.shading = medium ? geometry::LayerShading::medium : geometry::LayerShading::source;
        changed = true;
    }
    return changed;
}

}  // namespace kiri::preview
