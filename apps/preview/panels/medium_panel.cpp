// The fog's optics and motion (the scene's "medium" section, docs/medium.md): shared by every
// renderer, so an edit here applies to the layers on the next frame (and to the volume
// renderers). Playing the time drifts and dissipates the fog in real time. Ranges and
// tooltips are the medium's field list's (medium_options.hpp).
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
    if (field_slider("visibility (m)", visibility, geometry::field_named(o, "visibility"), "%.0f")) {
        o.extinction = geometry::extinction_from_visibility(visibility);
        changed = true;
    }
    ImGui::TextDisabled("extinction %.4f 1/m", o.extinction);
    changed |= edit("albedo", o, o.albedo, "%.3f");
    changed |= edit("anisotropy g", o, o.anisotropy, "%.2f");
    changed |= edit("top density", o, o.top_density, "%.2f");
    changed |= edit("multiple scattering", o, o.multiple_scattering);
    if (o.multiple_scattering == geometry::MultipleScattering::octaves)
        changed |= edit("scattering octaves", o, o.scattering_octaves);
    changed |= edit("detail", o, o.detail, "%.2f");
    changed |= edit("detail scale (m)", o, o.detail_scale, "%.0f");
    changed |= edit("wind (m/s)", o, o.wind, "%.1f");
    changed |= edit("dissipation half-life (s)", o, o.dissipation_half_life, "%.0f");
    changed |= edit("time (s)", o, o.time, "%.0f");
    ImGui::SameLine();
    changed |= ImGui::Checkbox("play", &view.play_time);
    bool medium = scene.layers.shading == geometry::LayerShading::medium;
    if (ImGui::Checkbox("layers shaded from the medium", &medium)) {
        scene.layers.shading = medium ? geometry::LayerShading::medium : geometry::LayerShading::source;
        changed = true;
    }
    field_tooltip(geometry::field_of(scene.layers, scene.layers.shading));
    return changed;
}

}  // namespace kiri::preview
