// Sun and sky light: applied on the next frame, nothing to recompute.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <imgui.h>

#include "panels/panels.hpp"
#include "panels/widgets.hpp"

namespace kiri::preview {

bool sun_panel(geometry::Scene& scene)
{
    if (!ImGui::CollapsingHeader("Sun", ImGuiTreeNodeFlags_DefaultOpen))
        return false;
    geometry::SunSpec& s = scene.sun;
    bool changed = direction_widget("direction", s.direction);
    // The same direction as numbers: compass azimuth and elevation, always a unit vector.
    const glm::dvec3 d = glm::normalize(s.direction);
    double azimuth = std::fmod(450.0 - std::atan2(d.y, d.x) * 180.0 / M_PI, 360.0);
    double elevation = std::asin(std::clamp(d.z, -1.0, 1.0)) * 180.0 / M_PI;
    bool moved = slider("azimuth (deg)", azimuth, 0.0, 360.0, "%.0f");
    moved |= slider("elevation (deg)", elevation, -10.0, 90.0, "%.1f");
    if (moved) {
        const double a = (90.0 - azimuth) * M_PI / 180.0, e = elevation * M_PI / 180.0;
        s.direction = {std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
        changed = true;
    }
    changed |= color_edit("colour", s.color);
    changed |= edit("intensity", s, s.intensity, "%.2f");
    changed |= color_edit("sky ambient", s.ambient);
    return changed;
}

}  // namespace kiri::preview
