// Froxel volumetric fog (the scene's "froxel" section, docs/froxel.md): the froxel grid, how its
// depth slices are spread, fog-aware slicing, temporal filtering and the optional height fog.
// Every control applies on the next frame (the renderer reruns its passes); drawn in the froxel
// and combined render modes.
#include <imgui.h>

#include "kiri/geometry/medium/medium.hpp"
#include "panels/panels.hpp"
#include "panels/widgets.hpp"

namespace kiri::preview {

bool froxel_panel(geometry::Scene& scene, const render::FroxelStats& stats)
{
    if (!ImGui::CollapsingHeader("Froxels"))
        return false;
    geometry::FroxelOptions& o = scene.froxel;
    bool changed = false;
    changed |= slider("froxels across", o.width, 16, 512);
    changed |= slider("froxels down", o.height, 9, 288);
    changed |= slider("depth slices", o.slices, 8, 256);
    int d = int(o.distribution);
    if (ImGui::Combo("slice distribution", &d, "exponential\0log2\0power\0")) {
        o.distribution = geometry::SliceDistribution(d);
        changed = true;
    }
    if (o.distribution == geometry::SliceDistribution::power)
        changed |= slider("power", o.power, 0.25, 8.0, "%.2f", true);
    else if (o.distribution == geometry::SliceDistribution::log2)
        changed |= slider("linear up to (m)", o.log2_scale, 1.0, 2000.0, "%.0f", true);
    changed |= ImGui::Checkbox("fog-aware slicing", &o.fog_aware);
    ImGui::SameLine();
    changed |= ImGui::Checkbox("temporal filtering", &o.temporal);
    changed |= ImGui::Checkbox("terrain shadows", &o.terrain_shadows);
    ImGui::SameLine();
    changed |= ImGui::Checkbox("fog shadows", &o.fog_shadows);
    geometry::HeightFog& h = o.height_fog;
    bool height_fog = h.enabled();
    if (ImGui::Checkbox("height fog", &height_fog)) {
        h.extinction = height_fog ? geometry::extinction_from_visibility(20000.0) : 0.0;
        changed = true;
    }
    if (h.enabled()) {
        double visibility = geometry::visibility_from_extinction(h.extinction);
        if (slider("visibility at the base (m)", visibility, 100.0, 200000.0, "%.0f", true)) {
            h.extinction = geometry::extinction_from_visibility(visibility);
            changed = true;
        }
        changed |= drag("base (m)", h.base, 5.0);
        changed |= slider("scale height (m)", h.scale_height, 10.0, 5000.0, "%.0f", true);
    }
    ImGui::TextDisabled("updates %d, shadow map %d; %s", stats.updates, stats.shadow_map_updates,
                        !stats.enabled      ? "off"
                            : stats.visible ? "in view"
                                            : "out of view");
    return changed;
}

}  // namespace kiri::preview
