// The fog's base surface (docs/fog.md): footprint, surface kind, fit and tessellation, and
// the figures of the last fit. Changes are refitted on the worker: a footprint, patch size or
// surface change rebuilds the control mesh, a fit option refits it, a tessellation option
// only retessellates.
#include <algorithm>
#include <cmath>

#include <imgui.h>

#include "kiri/geometry/terrain/terrain.hpp"
#include "panels/panels.hpp"
#include "panels/widgets.hpp"

namespace kiri::preview {
namespace {

enum FootprintKind { whole_terrain, rectangle, polygon };

FootprintKind kind_of(const geometry::Footprint& f)
{
    const auto& p = f.polygon;
    if (p.empty())
        return whole_terrain;
    if (p.size() == 4 && p[0].y == p[1].y && p[1].x == p[2].x && p[2].y == p[3].y && p[3].x == p[0].x)
        return rectangle;
    return polygon;
}

bool footprint_editor(geometry::FogSpec& f, const geometry::Terrain* terrain)
{
    FootprintKind kind = kind_of(f.footprint);
    int k = int(kind);
    bool changed = false;
    if (ImGui::Combo("footprint", &k, "whole terrain less a margin\0rectangle\0polygon\0") && k != int(kind)) {
        // A new kind starts from the area the old one covered (its bounding box).
        glm::dvec2 lo(-5000.0), hi(5000.0);
        if (!f.footprint.polygon.empty()) {
            lo = hi = f.footprint.polygon.front();
            for (const glm::dvec2& q : f.footprint.polygon)
                lo = glm::min(lo, q), hi = glm::max(hi, q);
        } else if (terrain) {
            const geometry::Bounds3 b = terrain->bounds();
            lo = glm::dvec2(b.min) + f.margin;
            hi = glm::dvec2(b.max) - f.margin;
        }
        f.footprint = k == whole_terrain ? geometry::Footprint{} : geometry::rectangle_footprint(lo, hi);
        return true;
    }
    switch (kind) {
    case whole_terrain:
        return field_slider("margin (m)", f.margin, geometry::field_of(f, f.margin, geometry::TerrainFootprintFields{}),
                            "%.0f");
    case rectangle: {
        auto& p = f.footprint.polygon;  // (min), (max.x, min.y), (max), (min.x, max.y)
        double lo[2] = {p[0].x, p[0].y}, hi[2] = {p[2].x, p[2].y};
        changed |= drag("min x (m)", lo[0], 20.0) | drag("min y (m)", lo[1], 20.0);
        changed |= drag("max x (m)", hi[0], 20.0) | drag("max y (m)", hi[1], 20.0);
        if (changed)
            f.footprint = geometry::rectangle_footprint({lo[0], lo[1]}, {hi[0], hi[1]});
        return changed;
    }
    case polygon: {
        auto& p = f.footprint.polygon;
        if (ImGui::TreeNode("points", "%zu points (x, y m)", p.size())) {
            for (std::size_t i = 0; i < p.size(); ++i) {
                ImGui::PushID(int(i));
                float xy[2] = {float(p[i].x), float(p[i].y)};
                if (ImGui::DragFloat2("##p", xy, 20.0f, 0.0f, 0.0f, "%.0f")) {
                    p[i] = {xy[0], xy[1]};
                    changed = true;
                }
                ImGui::PopID();
            }
            if (ImGui::Button("add a point")) {  // halfway along the closing edge
                p.push_back(0.5 * (p.back() + p.front()));
                changed = true;
            }
            ImGui::SameLine();
            if (p.size() > 3 && ImGui::Button("remove the last")) {
                p.pop_back();
                changed = true;
            }
            ImGui::TreePop();
        }
        return changed;
    }
    }
    return false;
}

void fit_figures(const geometry::PipelineProducts& fog)
{
    const geometry::FitReport& r = fog.surface->fit;
    ImGui::TextDisabled("%d patches, %zu triangles, %d solves", fog.surface->patches, fog.tessellation->mesh.n_faces(),
                        r.iterations);
    ImGui::TextDisabled("(world m) deviation max %.1f, rms %.1f", r.max_deviation, r.rms_deviation);
    ImGui::TextDisabled("min clearance %.1f m, fog over %.0f%% of samples", r.min_clearance, 100.0 * r.fog_fraction);
    ImGui::TextDisabled("tessellation error %.2f m", fog.tessellation->max_error);
}

}  // namespace

bool fog_panel(geometry::Scene& scene, const geometry::Terrain* terrain, const geometry::PipelineProducts* fog)
{
    if (!ImGui::CollapsingHeader("Fog surface", ImGuiTreeNodeFlags_DefaultOpen))
        return false;
    if (!scene.fog) {
        ImGui::TextDisabled("The scene has no fog section.");
        if (!ImGui::Button("add a fog blanket"))
            return false;
        scene.fog = geometry::FogSpec{};
        scene.fog->margin = 1000.0;
        return true;
    }
    geometry::FogSpec& f = *scene.fog;
    // Fog placed by the terrain brings its own footprint and lake target (its own panel).
    const bool placed = f.placement.has_value();
    bool changed = false;
    if (placed)
        ImGui::TextDisabled("footprint, lake top and thickness: placed by the terrain");
    else
        changed |= footprint_editor(f, terrain);
    int kind = f.surface == geometry::SurfaceKind::gregory ? 0 : 1;
    if (ImGui::Combo("surface", &kind, "Gregory patches\0Catmull-Clark (OpenSubdiv)\0")) {
        f.surface = kind == 0 ? geometry::SurfaceKind::gregory : geometry::SurfaceKind::catmull_clark;
        changed = true;
    }
    changed |= edit("patch size (m)", f, f.patch_size, "%.0f");
    geometry::FitOptions& o = f.fit;
    int mode = o.mode == geometry::FitMode::blanket ? 0 : 1;
    if (!placed && ImGui::Combo("mode", &mode, "blanket\0lake\0")) {
        o.mode = mode == 0 ? geometry::FitMode::blanket : geometry::FitMode::lake;
        if (o.mode == geometry::FitMode::lake && o.altitude == 0.0 && terrain)  // a third of the way up
            o.altitude = (terrain->bounds().min.z + (terrain->bounds().max.z - terrain->bounds().min.z) / 3.0) /
                scene.terrain.exaggeration;
        changed = true;
    }
    ImGui::TextDisabled("heights in metres of the DEM");
    if (placed) {
    } else if (o.mode == geometry::FitMode::blanket) {
        changed |= edit("offset (m)", o, o.offset, "%.0f");
        changed |= edit("clearance (m)", o, o.clearance, "%.0f");
        changed |= edit("smoothing (m)", o, o.smoothing_length, "%.0f");
    } else {
        changed |= field_drag("fog top (m)", o.altitude, geometry::field_of(o, o.altitude), 2.0);
    }
    if (!placed)
        changed |= edit("thickness (m)", o, o.thickness, "%.0f");
    changed |= edit("smoothness", o, o.smoothness, "%.4f");
    if (ImGui::TreeNode("fit samples")) {
        changed |= edit("samples per patch side", o, o.samples_per_patch);
        ImGui::SameLine();
        ImGui::TextDisabled(o.samples_per_patch == 0 ? "(0: 4)" : "");
        changed |= slider("active-set iterations", o.max_active_set_iterations, 1, 200);
        ImGui::TreePop();
    }
    geometry::TessellationOptions& t = f.tessellation;
    bool adaptive = t.tolerance > 0.0;
    if (ImGui::Checkbox("adaptive tessellation", &adaptive)) {
        t.tolerance = adaptive ? 1.0 : 0.0;
        changed = true;
    }
    if (adaptive) {
        changed |= edit("tolerance (m)", t, t.tolerance, "%.2f");
        changed |= edit("finest level", t, t.max_level);
    } else {
        changed |= edit("tessellation level", t, t.level);
    }
    if (fog)
        fit_figures(*fog);
    if (ImGui::Button("remove the fog section")) {
        scene.fog.reset();
        changed = true;
    }
    return changed;
}

}  // namespace kiri::preview
