// Fog placed by the terrain (docs/placement.md): the fill regions (seeds, fog top, thickness
// limits, the valley threshold), the night's flow and the morning's burn-off. An edit places the
// fog again on the worker, then refits the lake surface and rebuilds what follows. Heights are
// metres of the DEM, like the scene's keys.
#include <string>

#include <imgui.h>

#include "kiri/geometry/terrain/terrain.hpp"
#include "panels/panels.hpp"
#include "panels/widgets.hpp"

namespace kiri::preview {
namespace {

bool seed_points(std::vector<glm::dvec2>& points)
{
    bool changed = false;
    if (!ImGui::TreeNode("seed points", "%zu seed points (x, y m)", points.size()))
        return false;
    for (std::size_t i = 0; i < points.size(); ++i) {
        ImGui::PushID(int(i));
        float xy[2] = {float(points[i].x), float(points[i].y)};
        if (ImGui::DragFloat2("##p", xy, 20.0f, 0.0f, 0.0f, "%.0f")) {
            points[i] = {xy[0], xy[1]};
            changed = true;
        }
        ImGui::PopID();
    }
    if (ImGui::Button("add a point")) {  // beside the last, so it is visible at once
        points.push_back(points.back() + glm::dvec2(500.0, 0.0));
        changed = true;
    }
    if (points.size() > 1) {
        ImGui::SameLine();
        if (ImGui::Button("remove the last")) {
            points.pop_back();
            changed = true;
        }
    }
    ImGui::TreePop();
    return changed;
}

bool region_editor(geometry::FillRegionSpec& r)
{
    bool changed = false;
    int kind = int(r.seeds);
    // A mask comes from a file: offered only when the scene has one.
    const char* kinds = r.seeds == geometry::SeedKind::mask ? "seed points\0every basin\0valleys\0mask file\0"
                                                            : "seed points\0every basin\0valleys\0";
    if (ImGui::Combo("seeds", &kind, kinds) && kind != int(r.seeds)) {
        r.seeds = geometry::SeedKind(kind);
        if (r.seeds == geometry::SeedKind::points && r.points.empty())
            r.points.push_back({0.0, 0.0});
        changed = true;
    }
    if (r.seeds == geometry::SeedKind::points)
        changed |= seed_points(r.points);
    else if (r.seeds == geometry::SeedKind::valleys)
        changed |= edit("valley threshold", r.valleys, r.valleys.threshold, "%.2f");
    else if (r.seeds == geometry::SeedKind::mask)
        ImGui::TextDisabled("mask %s", r.mask_path.filename().string().c_str());
    changed |= field_drag("fog top (m)", r.top, geometry::field_of(r, r.top), 2.0);
    changed |= edit("min thickness (m)", r, r.min_thickness, "%.0f");
    bool limit = r.max_thickness > 0.0;
    if (ImGui::Checkbox("max thickness", &limit)) {
        r.max_thickness = limit ? 200.0 : 0.0;
        changed = true;
    }
    if (limit) {
        ImGui::SameLine();
        ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.5f);
        changed |= edit("##max", r, r.max_thickness, "%.0f m");
    }
    changed |= edit("density profile", r, r.profile, "%.2f");
    return changed;
}

bool flow_editor(geometry::PlacementSpec& p)
{
    bool on = p.flow.has_value();
    bool changed = false;
    if (ImGui::Checkbox("flow (the night's wind)", &on)) {
        if (on)
            p.flow = geometry::FlowOptions{.wind = {2.0, 0.0}};
        else
            p.flow.reset();
        changed = true;
    }
    if (!p.flow)
        return changed;
    geometry::FlowOptions& flow = *p.flow;
    changed |= edit("wind (m/s)", flow, flow.wind, "%.1f");
    changed |= field_slider("flow time (h)", flow.duration, geometry::field_of(flow, flow.duration), "%.1f", 3600.0);
    return changed;
}

bool burn_off_editor(geometry::PlacementSpec& p)
{
    bool on = p.burn_off.has_value();
    bool changed = false;
    if (ImGui::Checkbox("burn-off (the morning's sun)", &on)) {
        if (on)
            p.burn_off = geometry::BurnOffOptions{};
        else
            p.burn_off.reset();
        changed = true;
    }
    if (!p.burn_off)
        return changed;
    geometry::BurnOffOptions& burn_off = *p.burn_off;
    changed |= edit("time of day (h)", burn_off, burn_off.time, "%.2f");
    changed |= edit("day of the year", burn_off, burn_off.day_of_year);
    return changed;
}

void figures(const geometry::PlacedFog& placed, double exaggeration)
{
    const geometry::ColumnFigures& f = placed.figures;
    const double e = exaggeration > 0.0 ? exaggeration : 1.0;
    ImGui::TextDisabled("fog over %.1f km^2, %.3f km^3", f.area_m2 * 1e-6, f.volume_m3 * 1e-9 / e);
    ImGui::TextDisabled("thickness mean %.0f m, max %.0f m", f.mean_thickness / e, f.max_thickness / e);
    ImGui::TextDisabled("outline: %d polygons, %zu vertices", placed.outline.components, placed.outline.vertices);
    ImGui::TextDisabled("fill %.2f s, outline %.2f s", placed.seconds_fill, placed.seconds_outline);
    if (placed.flow)
        ImGui::TextDisabled("flow: spilled %.3f km^3, %.2f s", placed.flow->spilled_m3 * 1e-9 / e, placed.seconds_flow);
    if (placed.burn_off)
        ImGui::TextDisabled("burn-off: sun %.1f deg up, base lifted to %.0f m", placed.burn_off->sun_elevation_deg,
                            placed.burn_off->lifted_base / e);
}

}  // namespace

bool placement_panel(geometry::Scene& scene, const geometry::Terrain* terrain, const geometry::PipelineProducts* fog)
{
    if (!scene.fog)
        return false;
    if (!ImGui::CollapsingHeader("Fog placed by the terrain", ImGuiTreeNodeFlags_DefaultOpen))
        return false;
    geometry::FogSpec& spec = *scene.fog;
    if (!spec.placement) {
        ImGui::TextDisabled("The fog's footprint and top are set by hand.");
        if (!terrain || !ImGui::Button("fill every basin instead"))
            return false;
        // Up to a third of the way from the lowest ground to the highest, in metres of the DEM.
        const geometry::Bounds3 b = terrain->bounds();
        geometry::FillRegionSpec region;
        region.seeds = geometry::SeedKind::all;
        region.top = (b.min.z + (b.max.z - b.min.z) / 3.0) / scene.terrain.exaggeration;
        spec.placement = geometry::PlacementSpec{};
        spec.placement->regions = {region};
        spec.footprint = {};
        spec.fit.mode = geometry::FitMode::lake;
        return true;
    }
    geometry::PlacementSpec& p = *spec.placement;
    ImGui::TextDisabled("heights in metres of the DEM");
    bool changed = false;
    for (std::size_t i = 0; i < p.regions.size(); ++i) {
        ImGui::PushID(int(i));
        if (p.regions.size() > 1)
            ImGui::Text("region %zu", i + 1);
        changed |= region_editor(p.regions[i]);
        ImGui::PopID();
    }
    changed |= flow_editor(p);
    changed |= burn_off_editor(p);
    if (fog && fog->placed)
        figures(*fog->placed, scene.terrain.exaggeration);
    if (ImGui::Button("set the footprint by hand")) {  // a lake at the first region's top
        spec.fit.mode = geometry::FitMode::lake;
        spec.fit.altitude = p.regions.front().top;
        spec.placement.reset();
        return true;
    }
    return changed;
}

}  // namespace kiri::preview
