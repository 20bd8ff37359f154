// The timings overlay: frame times, each render pass's device and issue time, what was uploaded,
// the fog's own counters (particles, attenuation buffer builds: a static view rebuilds nothing),
// and the recomputation stages (runs, last CPU time), with progress while one runs.
#include <imgui.h>

#include "panels/panels.hpp"

namespace kiri::preview {

void stats_overlay(const FrameTimes& times, const render::FrameStats& stats, const FogCounts& fog,
                   const PipelineStatus& pipeline)
{
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_Always);
    ImGui::SetNextWindowBgAlpha(0.5f);
    ImGui::Begin("timings", nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoInputs |
                     ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav);
    ImGui::Text("frame %.1f ms, 3D view %.1f ms at %dx%d", times.loop_ms, times.scene_ms, times.scene_width,
                times.scene_height);
    ImGui::TextDisabled("3D frames drawn %lld, shown again %lld", times.scene_frames, times.reused_frames);
    if (ImGui::BeginTable("passes", 3, ImGuiTableFlags_SizingFixedFit)) {
        ImGui::TableSetupColumn("pass");
        ImGui::TableSetupColumn("GPU ms");
        ImGui::TableSetupColumn("CPU ms");
        ImGui::TableHeadersRow();
        for (const render::PassTime& p : stats.passes) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(p.pass.c_str());
            ImGui::TableNextColumn();
            ImGui::Text("%8.2f", p.gpu_ms);
            ImGui::TableNextColumn();
            ImGui::Text("%8.2f", p.cpu_ms);
        }
        ImGui::EndTable();
    }
    ImGui::Text("layers drawn %d of %d triangles each, GPU uploads this frame %d, sun's shadow map built %d times",
                stats.layers + (stats.layers > 0), stats.layer_triangles, stats.uploads, stats.shadow_map_updates);
    if (fog.froxels) {
        const render::FroxelStats& f = stats.froxel;
        ImGui::Text("froxel passes: ran in %d frames (this frame %s); %s", f.updates, f.updated ? "yes" : "no",
                    f.visible ? "in view" : "out of view");
    }
    if (fog.particles > 0) {
        ImGui::Text("particles %zu (drawn %d)", fog.particles, stats.particles);
        ImGui::Text("attenuation buffer: builds %d (this frame %d), last %.1f ms", fog.attenuation_builds,
                    stats.attenuation_rebuilds, fog.attenuation_build_ms);
    }
    if (ImGui::BeginTable("stages", 3, ImGuiTableFlags_SizingFixedFit)) {
        ImGui::TableSetupColumn("stage");
        ImGui::TableSetupColumn("rebuilds");
        ImGui::TableSetupColumn("last s");
        ImGui::TableHeadersRow();
        for (int i = 0; i < stage_count; ++i) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(stage_name(i));
            ImGui::TableNextColumn();
            ImGui::Text("%5d", pipeline.stages[i].runs);
            ImGui::TableNextColumn();
            ImGui::Text("%7.3f", pipeline.stages[i].last_seconds);
        }
        ImGui::EndTable();
    }
    if (pipeline.busy) {
        char label[96];
        std::snprintf(label, sizeof label, "%s %.1f s", stage_name(pipeline.stage), pipeline.stage_seconds);
        // Stages done out of all of them: coarse, but it moves and names what runs.
        ImGui::ProgressBar(float(pipeline.stage + 0.5f) / float(stage_count), ImVec2(260.0f, 0.0f), label);
    } else {
        ImGui::TextDisabled("up to date (edit %llu)", static_cast<unsigned long long>(pipeline.finished));
    }
    ImGui::End();
}

}  // namespace kiri::preview
