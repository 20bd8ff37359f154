// The fog as particles (the scene's "particles" section, docs/particles.md). Sampling options
// resample the Medium on the worker (~1 s for 60k particles); the attenuation buffer's
// resolution and format and the billboards' soft edge apply on the next frame (the buffer is
// rebuilt once). Drawn in the particles and combined render modes. Ranges and tooltips are the
// particles' field list's (particles.hpp).
#include <algorithm>

#include <imgui.h>

#include "kiri/render/attenuation.hpp"
#include "panels/panels.hpp"
#include "panels/widgets.hpp"

namespace kiri::preview {

bool particles_panel(geometry::Scene& scene, const geometry::ParticleCloud* cloud,
                     const render::AttenuationBuffer& buffer)
{
    if (!ImGui::CollapsingHeader("Particles"))
        return false;
    geometry::ParticleOptions& o = scene.particles;
    bool changed = false;
    bool by_spacing = o.spacing > 0.0;
    if (ImGui::Checkbox("by spacing", &by_spacing)) {
        // Starts from the spacing the last cloud had, so the count barely moves.
        o.spacing = by_spacing ? (cloud && cloud->spacing > 0.0 ? cloud->spacing : 200.0) : 0.0;
        changed = true;
    }
    if (by_spacing)
        changed |= edit("spacing (m)", o, o.spacing, "%.0f");
    else
        changed |= edit("count", o, o.count);
    changed |= edit("radius scale", o, o.radius_scale, "%.2f");
    bool own_albedo = o.albedo >= 0.0;
    if (ImGui::Checkbox("own albedo", &own_albedo)) {
        o.albedo = own_albedo ? scene.medium.albedo : -1.0;
        changed = true;
    }
    if (own_albedo) {
        ImGui::SameLine();
        ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.5f);
        changed |= edit("##albedo", o, o.albedo, "%.3f");
    } else {
        ImGui::SameLine();
        ImGui::TextDisabled("(the medium's %.3f)", scene.medium.albedo);
    }
    int seed = int(std::min<std::uint64_t>(o.seed, 1000000));
    if (ImGui::InputInt("seed", &seed)) {
        o.seed = std::uint64_t(std::max(seed, 0));
        changed = true;
    }
    ImGui::TextUnformatted("attenuation buffer");
    changed |= edit("voxels per side", o, o.resolution);
    changed |= field_combo("format", o.half_float, geometry::field_of(o, o.half_float));
    changed |= edit("soft edge (m)", o, o.soft_edge, "%.0f");
    changed |= edit("near: coarser by", o, o.near_scale);
    changed |= edit("near: from radius (px)", o, o.near_pixels, "%.0f");
    changed |= edit("near field (radii)", o, o.near_field, "%.1f");
    changed |= ImGui::Checkbox("match the Medium", &o.match_medium);
    if (cloud)
        ImGui::TextDisabled("%zu particles, spacing %.0f m", cloud->particles.size(), cloud->spacing);
    if (buffer.rebuild_count() > 0) {
        const auto& size = buffer.grid().size;
        ImGui::TextDisabled("buffer %dx%dx%d, %.1f MiB, built %d times, last %.1f ms", size[0], size[1], size[2],
                            double(buffer.texture_bytes()) / 1048576.0, buffer.rebuild_count(), buffer.last_build_ms());
    }
    return changed;
}

}  // namespace kiri::preview
