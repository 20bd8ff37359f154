#include "panel.hpp"

#include <cmath>
#include <cstdio>

#include <imgui.h>

namespace kiri::preview {
namespace {

bool slider(const char* label, double& value, double lo, double hi, const char* format = "%.1f", bool log = false)
{
    float v = float(value);
    const bool changed =
        ImGui::SliderFloat(label, &v, float(lo), float(hi), format, log ? ImGuiSliderFlags_Logarithmic : 0);
    if (changed)
        value = v;
    return changed;
}

}  // namespace

bool terrain_section(geometry::Scene& scene)
{
    if (!ImGui::CollapsingHeader("Terrain", ImGuiTreeNodeFlags_DefaultOpen))
        return false;
    return slider("exaggeration", scene.terrain.exaggeration, 0.1, 5.0, "%.2f");
}

bool sun_section(geometry::Scene& scene)
{
    if (!ImGui::CollapsingHeader("Sun", ImGuiTreeNodeFlags_DefaultOpen))
        return false;
    glm::dvec3& d = scene.sun.direction;
    // Direction as azimuth (from east, counter-clockwise) and elevation: always a unit vector.
    double azimuth = std::atan2(d.y, d.x) * 180.0 / M_PI;
    double elevation = std::asin(std::fmax(-1.0, std::fmin(1.0, d.z / std::fmax(glm::length(d), 1e-12)))) * 180.0 / M_PI;
    bool changed = slider("azimuth", azimuth, -180.0, 180.0, "%.0f deg");
    changed |= slider("elevation", elevation, -5.0, 90.0, "%.0f deg");
    if (changed) {
        const double a = azimuth * M_PI / 180.0, e = elevation * M_PI / 180.0;
        d = {std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
    }
    float color[3] = {float(scene.sun.color.r), float(scene.sun.color.g), float(scene.sun.color.b)};
    if (ImGui::ColorEdit3("colour", color)) {
        scene.sun.color = {color[0], color[1], color[2]};
        changed = true;
    }
    changed |= slider("intensity", scene.sun.intensity, 0.0, 10.0, "%.2f");
    return changed;
}

bool fog_section(geometry::Scene& scene)
{
    if (!ImGui::CollapsingHeader("Fog surface", ImGuiTreeNodeFlags_DefaultOpen))
        return false;
    if (!scene.fog) {
        if (ImGui::Button("Add a fog blanket")) {
            scene.fog = geometry::FogSpec{};
            scene.fog->patch_size = 1000.0;
            scene.fog->margin = 1000.0;
            return true;
        }
        return false;
    }
    geometry::FogSpec& f = *scene.fog;
    bool changed = false;
    int kind = f.surface == geometry::SurfaceKind::gregory ? 0 : 1;
    if (ImGui::Combo("surface", &kind, "Gregory patches\0Catmull-Clark (OpenSubdiv)\0")) {
        f.surface = kind == 0 ? geometry::SurfaceKind::gregory : geometry::SurfaceKind::catmull_clark;
        changed = true;
    }
    int mode = f.fit.mode == geometry::FitMode::blanket ? 0 : 1;
    if (ImGui::Combo("mode", &mode, "blanket\0lake\0")) {
        f.fit.mode = mode == 0 ? geometry::FitMode::blanket : geometry::FitMode::lake;
        if (f.fit.mode == geometry::FitMode::lake && f.fit.altitude == 0.0)
            f.fit.altitude = 450.0;
        changed = true;
    }
    changed |= slider("patch size (m)", f.patch_size, 250.0, 4000.0, "%.0f", true);
    if (f.footprint.polygon.empty())
        changed |= slider("margin (m)", f.margin, 0.0, 5000.0, "%.0f");
    if (f.fit.mode == geometry::FitMode::blanket) {
        changed |= slider("offset (m)", f.fit.offset, -100.0, 500.0, "%.0f");
        changed |= slider("clearance (m)", f.fit.clearance, 0.0, f.fit.thickness, "%.0f");
        changed |= slider("smoothing (m)", f.fit.smoothing_length, 0.0, 3000.0, "%.0f");
    } else {
        changed |= slider("fog top (m)", f.fit.altitude, 0.0, 2000.0, "%.0f");
    }
    changed |= slider("thickness (m)", f.fit.thickness, std::fmax(f.fit.clearance, 10.0), 1000.0, "%.0f");
    changed |= slider("smoothness", f.fit.smoothness, 0.0, 1.0, "%.3f", true);
    changed |= ImGui::SliderInt("tessellation", &f.tessellation.level, 1, 32);
    return changed;
}

bool layers_section(geometry::Scene& scene, PanelState& state)
{
    if (!ImGui::CollapsingHeader("Layers", ImGuiTreeNodeFlags_DefaultOpen))
        return false;
    geometry::LayerOptions& o = scene.layers;
    bool changed = ImGui::Checkbox("show fog", &state.show_fog);
    changed |= ImGui::SliderInt("layers", &o.count, 1, 100);
    o.max_count = std::max(o.max_count, o.count);
    changed |= ImGui::Checkbox("spacing rule (2.8, 2.9)", &o.narrowing);
    ImGui::SameLine();
    changed |= ImGui::Checkbox("scale rule (2.10)", &o.enlargement);
    changed |= slider("opacity", o.opacity, 0.0, 0.9, "%.3f");
    changed |= slider("fade width", o.texture.fade_width, 0.02, 1.0, "%.2f");
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
    changed |= slider("layer resolution", state.layer_resolution, 0.125, 1.0, "%.2f");
    return changed;
}

void view_section(const geometry::Scene& scene, PanelState& state)
{
    if (!ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen))
        return;
    for (std::size_t i = 0; i < scene.cameras.size(); ++i) {
        if (i > 0)
            ImGui::SameLine();
        if (ImGui::Button(scene.cameras[i].name.c_str()))
            state.bookmark = int(i);
    }
    ImGui::Checkbox("control mesh", &state.control_wireframe);
    ImGui::SameLine();
    ImGui::Checkbox("patch boundaries", &state.patch_wireframe);
    ImGui::Checkbox("fit deviation", &state.deviation_map);
    if (state.deviation_map)
        ImGui::Text("surface - target: blue -%.0f m, white 0, red +%.0f m", state.deviation_scale,
                    state.deviation_scale);
    state.focus_fog = ImGui::Button("focus on fog (F)");
    ImGui::SameLine();
    state.reset_camera = ImGui::Button("reset (R)");
    state.screenshot_requested = ImGui::Button("screenshot (P)");
    ImGui::SameLine();
    state.save_requested = ImGui::Button("save scene");
    ImGui::TextWrapped("Left drag: orbit. Right drag: pan. Wheel: zoom. WASD + Q/E: fly.");
    if (!state.message.empty())
        ImGui::TextWrapped("%s", state.message.c_str());
}

void overlay(const render::FrameStats& stats, const WorkStatus& work, double frame_ms)
{
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_Always);
    ImGui::SetNextWindowBgAlpha(0.45f);
    ImGui::Begin("timings", nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoInputs);
    ImGui::Text("frame %.1f ms (%.0f FPS)", frame_ms, frame_ms > 0.0 ? 1000.0 / frame_ms : 0.0);
    for (const render::PassTime& p : stats.passes)
        ImGui::Text("  %-10s GPU %6.2f ms  CPU %6.2f ms", p.pass.c_str(), p.gpu_ms, p.cpu_ms);
    ImGui::Text("layers drawn: %d, uploads this frame: %d", stats.layers + (stats.layers > 0), stats.uploads);
    ImGui::Text("rebuilds: terrain %d (%.2f s), fog %d (%.2f s)", work.terrain_rebuilds, work.terrain_seconds,
                work.fog_rebuilds, work.fog_seconds);
    if (work.busy)
        ImGui::Text("recomputing... %.1f s", work.running_seconds);
    ImGui::End();
}

}  // namespace kiri::preview
