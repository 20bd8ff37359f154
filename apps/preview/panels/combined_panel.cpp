// Combined rendering (the scene's "combined" section, docs/combined.md): which renderer draws
// the fog at each distance and height, and the quality presets that set every renderer's
// budget at once. Applied on the next frame; a new particle share or depth resamples the
// particles.
#include <imgui.h>

#include "kiri/geometry/medium/fog_partition.hpp"
#include "panels/panels.hpp"
#include "panels/widgets.hpp"

namespace kiri::preview {
namespace {

// The preset's values replace the scene's own: choosing a preset in the panel is choosing its
// budgets (a scene file's keys win over its "quality" key only when it is loaded).
void apply_preset(geometry::Scene& scene, geometry::Quality q)
{
    const geometry::QualityPreset p = geometry::quality_preset(q);
    scene.layers.count = p.layers;
    scene.layers.resolution = p.layer_resolution;
    scene.particles.count = p.particles;
    scene.particles.resolution = p.attenuation_resolution;
    scene.froxel.width = p.froxel_width;
    scene.froxel.height = p.froxel_height;
    scene.froxel.slices = p.froxel_slices;
    scene.froxel.pixel_steps = p.froxel_pixel_steps;
    scene.combined.particle_share = p.particle_share;
    scene.quality = q;
}

bool quality_combo(geometry::Scene& scene)
{
    const geometry::Quality all[] = {geometry::Quality::low, geometry::Quality::medium, geometry::Quality::high,
                                     geometry::Quality::ultra};
    const char* shown = scene.quality ? geometry::to_string(*scene.quality) : "as the scene says";
    bool changed = false;
    if (ImGui::BeginCombo("quality", shown)) {
        for (geometry::Quality q : all)
            if (ImGui::Selectable(geometry::to_string(q), scene.quality == q)) {
                apply_preset(scene, q);
                changed = true;
            }
        ImGui::EndCombo();
    }
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "a preset of layer count and resolution, particles and their attenuation buffer, the froxel "
            "volume and the particles' share (docs/combined.md); choosing one sets them all");
    return changed;
}

}  // namespace

bool combined_panel(geometry::Scene& scene)
{
    if (!ImGui::CollapsingHeader("Combined and quality"))
        return false;
    bool changed = quality_combo(scene);
    geometry::FogPartition& o = scene.combined;
    // By default the froxels draw every distance; the layers can take the far fog.
    bool layers_far = o.near_end < geometry::fog_partition_everywhere;
    if (ImGui::Checkbox("layers draw the far fog", &layers_far)) {
        o.near_start = layers_far ? 400.0 : geometry::fog_partition_everywhere;
        o.near_end = layers_far ? 1600.0 : geometry::fog_partition_everywhere;
        changed = true;
    }
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "off (the default): the froxels draw the fog at every distance; on: the layers draw it "
            "beyond the hand-over below (docs/combined.md)");
    if (layers_far) {
        changed |= edit("froxels up to (m)", o, o.near_start, "%.0f");
        changed |= edit("layers from (m)", o, o.near_end, "%.0f");
    }
    changed |= edit("particle share", o, o.particle_share, "%.2f");
    changed |= edit("particle band", o, o.particle_band, "%.2f");
    changed |= edit("particle depth (radii)", o, o.particle_depth, "%.1f");
    if (o.near_end < o.near_start)  // the sliders move one at a time: keep the hand-over ordered
        o.near_end = o.near_start;
    return changed;
}

}  // namespace kiri::preview
