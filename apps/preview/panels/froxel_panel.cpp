// Froxel volumetric fog (the scene's "froxel" section, docs/froxel.md): the froxel grid, how its
// depth slices are spread, fog-aware slicing, temporal filtering and the optional height fog.
// Every control applies on the next frame (the renderer reruns its passes); drawn in the froxel
// and combined render modes. Ranges and tooltips are the froxels' field lists'
// (froxel_options.hpp, height_fog.hpp).
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
    changed |= edit("froxels across", o, o.width);
    changed |= edit("froxels down", o, o.height);
    changed |= edit("depth slices", o, o.slices);
    changed |= edit("slice distribution", o, o.distribution);
    if (o.distribution == geometry::SliceDistribution::power)
        changed |= edit("power", o, o.power, "%.2f");
    else if (o.distribution == geometry::SliceDistribution::log2)
        changed |= edit("linear up to (m)", o, o.log2_scale, "%.0f");
    changed |= edit("fog-aware slicing", o, o.fog_aware);
    ImGui::SameLine();
    changed |= edit("temporal filtering", o, o.temporal);
    changed |= edit("terrain shadows", o, o.terrain_shadows);
    ImGui::SameLine();
    changed |= edit("fog shadows", o, o.fog_shadows);
    geometry::HeightFog& h = o.height_fog;
    bool height_fog = h.enabled();
    if (ImGui::Checkbox("height fog", &height_fog)) {
        h.extinction = height_fog ? geometry::extinction_from_visibility(20000.0) : 0.0;
        changed = true;
    }
    if (h.enabled()) {
        double visibility = geometry::visibility_from_extinction(h.extinction);
        if (field_slider("visibility at the base (m)", visibility, geometry::field_named(h, "visibility"), "%.0f")) {
            h.extinction = geometry::extinction_from_visibility(visibility);
            changed = true;
        }
        changed |= field_drag("base (m)", h.base, geometry::field_of(h, h.base), 5.0);
        changed |= edit("scale height (m)", h, h.scale_height, "%.0f");
    }
    ImGui::TextDisabled("updates %d; %s", stats.updates,
                        !stats.enabled      ? "off"
                            : stats.visible ? "in view"
                                            : "out of view");
    return changed;
}

}  // namespace kiri::preview
