#pragma once
// The preview's parameter panel (Dear ImGui): one section per stage, editing the scene in
// place, and the timings overlay. Each section returns true when it changed something.
#include <string>

#include "kiri/geometry/scene.hpp"
#include "kiri/render/renderer.hpp"

namespace kiri::preview {

struct PanelState {
    bool show_fog = true;
    bool control_wireframe = false, patch_wireframe = false, deviation_map = false;
    double deviation_scale = 0.0;  // metres at full colour, shown as the map's legend
    double layer_resolution = 0.5;
    bool save_requested = false, screenshot_requested = false, reset_camera = false, focus_fog = false;
    int bookmark = -1;  // a scene camera picked this frame
    std::string message;  // last error or saved path, shown at the bottom
};

struct WorkStatus {
    bool busy = false;
    double running_seconds = 0.0;
    double terrain_seconds = 0.0, fog_seconds = 0.0;
    int terrain_rebuilds = 0, fog_rebuilds = 0;
};

bool terrain_section(geometry::Scene& scene);
bool sun_section(geometry::Scene& scene);
bool fog_section(geometry::Scene& scene);
bool layers_section(geometry::Scene& scene, PanelState& state);
void view_section(const geometry::Scene& scene, PanelState& state);
void overlay(const render::FrameStats& stats, const WorkStatus& work, double frame_ms);

}  // namespace kiri::preview
