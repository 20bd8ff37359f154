#include "panels/widgets.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>
#include <imgui.h>

#include "fog_views.hpp"

namespace kiri::preview {
namespace {
constexpr double deg = M_PI / 180.0;
constexpr double lowest_elevation = -10.0;  // degrees at the rim

ImU32 to_u32(const glm::vec4& c) { return ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, c.a)); }
}  // namespace

bool slider(const char* label, double& value, double lo, double hi, const char* format, bool log)
{
    float v = float(value);
    const ImGuiSliderFlags flags = ImGuiSliderFlags_AlwaysClamp | (log ? ImGuiSliderFlags_Logarithmic : 0);
    if (!ImGui::SliderFloat(label, &v, float(lo), float(hi), format, flags))
        return false;
    value = v;
    return true;
}

bool slider(const char* label, int& value, int lo, int hi)
{
    return ImGui::SliderInt(label, &value, lo, hi, "%d", ImGuiSliderFlags_AlwaysClamp);
}

bool drag(const char* label, double& value, double speed, const char* format)
{
    float v = float(value);
    if (!ImGui::DragFloat(label, &v, float(speed), 0.0f, 0.0f, format))
        return false;
    value = v;
    return true;
}

bool color_edit(const char* label, glm::dvec3& rgb)
{
    float c[3] = {float(rgb.r), float(rgb.g), float(rgb.b)};
    if (!ImGui::ColorEdit3(label, c, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR))
        return false;
    rgb = {std::max(c[0], 0.0f), std::max(c[1], 0.0f), std::max(c[2], 0.0f)};
    return true;
}

bool direction_widget(const char* label, glm::dvec3& direction, float radius)
{
    ImGui::PushID(label);
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    const ImVec2 size(2.0f * radius + 20.0f, 2.0f * radius + 20.0f);
    ImGui::InvisibleButton("sky", size);
    const ImVec2 c(origin.x + size.x * 0.5f, origin.y + size.y * 0.5f);
    // Elevation e sits at (90 - e) / (90 - lowest) of the radius.
    const auto radius_of = [&](double elevation) {
        return float((90.0 - elevation) / (90.0 - lowest_elevation)) * radius;
    };
    bool changed = false;
    if (ImGui::IsItemActive()) {
        const ImVec2 m = ImGui::GetIO().MousePos;
        const double x = (m.x - c.x) / radius_of(0.0), y = -(m.y - c.y) / radius_of(0.0);  // north up
        const double r = std::min(std::hypot(x, y), double(radius_of(lowest_elevation) / radius_of(0.0)));
        const double elevation = 90.0 - r * 90.0, azimuth = std::atan2(y, x);
        direction = {std::cos(elevation * deg) * std::cos(azimuth), std::cos(elevation * deg) * std::sin(azimuth),
                     std::sin(elevation * deg)};
        changed = true;
    }
    ImDrawList* draw = ImGui::GetWindowDrawList();
    const ImU32 line = ImGui::GetColorU32(ImGuiCol_TextDisabled), text = ImGui::GetColorU32(ImGuiCol_Text);
    draw->AddCircleFilled(c, radius_of(lowest_elevation), IM_COL32(40, 40, 48, 255), 48);
    draw->AddCircleFilled(c, radius_of(0.0), IM_COL32(60, 90, 130, 255), 48);
    for (double e : {0.0, 30.0, 60.0})
        draw->AddCircle(c, radius_of(e), line, 48);
    const float r0 = radius_of(lowest_elevation) + 2.0f;
    draw->AddText(ImVec2(c.x - 4, c.y - r0 - 14), text, "N");
    draw->AddText(ImVec2(c.x + r0 + 1, c.y - 7), text, "E");
    draw->AddText(ImVec2(c.x - 4, c.y + r0), text, "S");
    draw->AddText(ImVec2(c.x - r0 - 10, c.y - 7), text, "W");
    const glm::dvec3 d = glm::length(direction) > 0.0 ? glm::normalize(direction) : glm::dvec3(0, 0, 1);
    const double elevation = std::asin(std::clamp(d.z, -1.0, 1.0)) / deg, azimuth = std::atan2(d.y, d.x);
    const float r = radius_of(std::max(elevation, lowest_elevation));
    const ImVec2 sun(c.x + r * float(std::cos(azimuth)), c.y - r * float(std::sin(azimuth)));
    draw->AddLine(c, sun, IM_COL32(255, 220, 120, 160));
    draw->AddCircleFilled(sun, 6.0f, IM_COL32(255, 210, 80, 255));
    ImGui::SameLine();
    ImGui::BeginGroup();
    ImGui::TextUnformatted(label);
    ImGui::Text("azimuth %.0f deg\n(from north, clockwise)", std::fmod(450.0 - azimuth / deg, 360.0));
    ImGui::Text("elevation %.1f deg", elevation);
    ImGui::TextDisabled("drag in the disc");
    ImGui::EndGroup();
    ImGui::PopID();
    return changed;
}

void color_legend(const char* low, const char* high, bool diverging)
{
    const ImVec2 p = ImGui::GetCursorScreenPos();
    const float width = ImGui::GetContentRegionAvail().x * 0.6f, height = ImGui::GetTextLineHeight();
    ImDrawList* draw = ImGui::GetWindowDrawList();
    constexpr int pieces = 16;
    for (int i = 0; i < pieces; ++i) {
        const double t0 = double(i) / pieces, t1 = double(i + 1) / pieces;
        const auto color = [&](double t) {
            return to_u32(diverging ? diverging_color(2.0 * t - 1.0) : sequential_color(t));
        };
        const ImU32 a = color(t0), b = color(t1);
        draw->AddRectFilledMultiColor(ImVec2(p.x + width * float(t0), p.y),
                                      ImVec2(p.x + width * float(t1), p.y + height), a, b, b, a);
    }
    ImGui::Dummy(ImVec2(width, height));
    ImGui::TextUnformatted(low);
    ImGui::SameLine(std::max(width - ImGui::CalcTextSize(high).x, 0.0f) + ImGui::GetStyle().WindowPadding.x);
    ImGui::TextUnformatted(high);
}

namespace {

// The field's slider ends: its widget range, else its range; an open end is nudged inside.
struct Ends {
    double lo, hi;
};
Ends ends(const geometry::FieldInfo& info)
{
    const geometry::Range& r = info.widget.bounded() ? info.widget : info.range;
    double lo = r.lo.value, hi = std::max(r.hi.value, r.lo.value);
    const double nudge = (hi - lo) * 1e-4;
    if (r.lo_open)
        lo += nudge;
    if (r.hi_open)
        hi -= nudge;
    return {lo, hi};
}

}  // namespace

void field_tooltip(const geometry::FieldInfo& info, bool integer)
{
    if (!ImGui::IsItemHovered())
        return;
    const std::string range = geometry::range_text(info.range, integer);
    ImGui::SetTooltip("%.*s%s%.*s%s%s\n%.*s", int(info.key.size()), info.key.data(), info.unit.empty() ? "" : " (",
                      int(info.unit.size()), info.unit.data(), info.unit.empty() ? "" : ")",
                      range.empty() ? "" : (" " + range).c_str(), int(info.doc.size()), info.doc.data());
}

bool field_slider(const char* label, double& value, const geometry::FieldInfo& info, const char* format,
                  double per_shown)
{
    const Ends e = ends(info);
    double shown = value / per_shown;
    const bool changed = slider(label, shown, e.lo / per_shown, e.hi / per_shown, format, info.log_widget);
    field_tooltip(info);
    if (changed)
        value = shown * per_shown;
    return changed;
}

bool field_slider(const char* label, int& value, const geometry::FieldInfo& info)
{
    const Ends e = ends(info);
    const ImGuiSliderFlags flags = ImGuiSliderFlags_AlwaysClamp | (info.log_widget ? ImGuiSliderFlags_Logarithmic : 0);
    const bool changed = ImGui::SliderInt(label, &value, int(std::ceil(e.lo)), int(std::floor(e.hi)), "%d", flags);
    field_tooltip(info, true);
    return changed;
}

bool field_slider(const char* label, glm::dvec2& value, const geometry::FieldInfo& info, const char* format)
{
    const Ends e = ends(info);
    float v[2] = {float(value.x), float(value.y)};
    const bool changed = ImGui::SliderFloat2(label, v, float(e.lo), float(e.hi), format);
    field_tooltip(info);
    if (changed)
        value = {v[0], v[1]};
    return changed;
}

bool field_drag(const char* label, double& value, const geometry::FieldInfo& info, double speed, const char* format)
{
    const bool changed = drag(label, value, speed, format);
    field_tooltip(info);
    return changed;
}

bool field_checkbox(const char* label, bool& value, const geometry::FieldInfo& info)
{
    const bool changed = ImGui::Checkbox(label, &value);
    field_tooltip(info);
    return changed;
}

bool choice_combo(const char* label, int& value, const geometry::FieldInfo& info)
{
    int index = 0;
    for (std::size_t k = 0; k < info.choices.size(); ++k)
        if (info.choices[k].value == value)
            index = int(k);
    bool changed = false;
    const std::string shown(info.choices.empty() ? std::string_view() : info.choices[std::size_t(index)].name);
    if (ImGui::BeginCombo(label, shown.c_str())) {
        for (std::size_t k = 0; k < info.choices.size(); ++k) {
            const std::string name(info.choices[k].name);
            if (ImGui::Selectable(name.c_str(), int(k) == index) && int(k) != index) {
                value = info.choices[k].value;
                changed = true;
            }
        }
        ImGui::EndCombo();
    }
    field_tooltip(info);
    return changed;
}

}  // namespace kiri::preview
