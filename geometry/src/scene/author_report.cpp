#include "kiri/geometry/scene/author_report.hpp"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "scene/fog_spec_json.hpp"

namespace kiri::geometry {
namespace {

using json = nlohmann::json;

const char* seed_kind(SeedKind k)
{
    switch (k) {
    case SeedKind::points: return "points";
    case SeedKind::all: return "all";
    case SeedKind::valleys: return "valleys";
    case SeedKind::mask: return "mask";
    }
    return "points";
}

json optics(const MediumOptions& m)
{
    const EngineFog e = engine_fog(m.extinction);
    // LWC for 7 um droplets (medium.hpp: sigma = 3 Q LWC / (4 rho_w r), Q = 2).
    const double lwc = m.extinction * 4.0 * 1e6 * 7e-6 / 6.0;
    return {{"extinction_per_m", m.extinction},
            {"visibility_m", visibility_from_extinction(m.extinction)},
            {"liquid_water_content_g_per_m3_at_7um", lwc},
            {"albedo", m.albedo},
            {"anisotropy_g", m.anisotropy},
            {"engines",
             {{"hdrp_fog_attenuation_distance_m", e.hdrp_attenuation_distance_m},
              {"unreal_exponential_height_fog_density", e.unreal_fog_density},
              {"godot_fog_density", e.godot_density}}}};
}

json placement(const Scene& scene, const PlacedFog& p)
{
    const double e = scene.terrain.exaggeration;
    const PlacementSpec& spec = *scene.fog->placement;
    json regions = json::array();
    for (std::size_t r = 0; r < p.fills.size(); ++r) {
        const FogFill& f = p.fills[r];
        json j = {{"top_m", f.top / e},
                  {"seeds", seed_kind(spec.regions[r].seeds)},
                  {"seed_cells", f.seed_cells},
                  {"cells", f.cells},
                  {"area_km2", f.area_m2 * 1e-6},
                  {"volume_m3", f.volume_m3 / e},
                  {"max_thickness_m", f.max_thickness / e},
                  {"mean_thickness_m", f.mean_thickness / e},
                  {"touches_border", f.touches_border},
                  {"spills", f.spills}};
        if (f.spills) {
            j["spill_level_m"] = f.spill_level / e;
            j["spill_point"] = {f.spill_point.x, f.spill_point.y};
        }
        regions.push_back(j);
    }
    const ColumnFigures& c = p.figures;
    json out = {{"regions", regions},
                {"fog",
                 {{"cells", c.cells},
                  {"area_km2", c.area_m2 * 1e-6},
                  {"volume_m3", c.volume_m3 / e},
                  {"max_thickness_m", c.max_thickness / e},
                  {"mean_thickness_m", c.mean_thickness / e},
                  {"top_min_m", c.top_min / e},
                  {"top_max_m", c.top_max / e},
                  {"bottom_min_m", c.bottom_min / e},
                  {"flat_top", p.flat}}},
                {"outline",
                 {{"polygons", p.outline.components},
                  {"vertices", p.outline.vertices},
                  {"tolerance_m", p.outline.tolerance},
                  {"dropped_components", p.outline.dropped}}}};
    if (p.valleys)
        out["valleys"] = {{"radii_m", p.valleys->radii}, {"cells", p.valleys->cells}};
    if (p.flow) {
        const FlowReport& f = *p.flow;
        out["flow"] = {{"steps", f.steps},
                       {"pools", f.pools},
                       {"volume_before_m3", f.volume_before_m3 / e},
                       {"volume_after_m3", f.volume_after_m3 / e},
                       {"spilled_m3", f.spilled_m3 / e},
                       {"stream_m3", f.stream_m3 / e},
                       {"outflow_m3", f.outflow_m3 / e},
                       {"evaporated_m3", f.evaporated_m3 / e},
                       {"max_set_up_m", f.max_tilt_m / e},
                       {"evaporation_depth_m", f.evaporation_depth_m / e}};
    }
    if (p.burn_off) {
        const BurnOffReport& b = *p.burn_off;
        out["burn_off"] = {{"latitude_deg", p.latitude},
                           {"sunrise_h", b.sunrise_hour},
                           {"sun_elevation_deg", b.sun_elevation_deg},
                           {"sun_hours_level", b.sun_hours_level},
                           {"lifted_base_m", b.lifted_base / e},
                           {"cells_before", b.cells_before},
                           {"cells_after", b.cells_after},
                           {"volume_before_m3", b.volume_before_m3 / e},
                           {"volume_after_m3", b.volume_after_m3 / e}};
    }
    out["timings_s"] = {{"valleys", p.seconds_valleys},           {"fill", p.seconds_fill},
                        {"flood_levels", p.seconds_flood_levels}, {"flow", p.seconds_flow},
                        {"burn_off", p.seconds_burn_off},         {"outline", p.seconds_outline}};
    return out;
}

// The fit, the counts and the tessellation of the authored base surface.
void surface_report(const PipelineProducts& products, const std::array<StageRecord, stage_count>& stages, json& j)
{
    const SurfaceSummary& s = *products.surface;
    const FitReport& f = s.fit;
    const Tessellation& t = *products.tessellation;
    const auto& levels = t.patch_level;
    int lo = levels.empty() ? 0 : levels[0], hi = lo;
    for (int l : levels) {
        lo = std::min(lo, l);
        hi = std::max(hi, l);
    }
    j["fit"] = {{"max_deviation_m", f.max_deviation},
                {"rms_deviation_m", f.rms_deviation},
                {"min_clearance_m", f.min_clearance},
                {"local_lift_m", f.local_lift},
                {"lift_m", f.lift},
                {"fog_fraction", f.fog_fraction},
                {"samples", f.samples},
                {"grid_vertex_samples", f.grid_vertex_samples},
                {"nodata_samples", f.nodata_samples},
                {"active_constraints", f.active_constraints},
                {"iterations", f.iterations},
                {"samples_per_patch", f.samples_per_patch}};
    j["counts"] = {{"patches", s.patches},
                   {"control_vertices", s.control_vertices},
                   {"snapped_boundary_vertices", s.snapped_boundary_vertices},
                   {"boundary_vertices", s.boundary_vertices},
                   {"triangles", t.mesh.n_faces()},
                   {"vertices", t.mesh.n_vertices()},
                   {"patch_level_min", lo},
                   {"patch_level_max", hi}};
    j["tessellation"] = {{"max_error_m", t.max_error}};
    const auto seconds = [&](Stage stage) { return stages[std::size_t(stage)].seconds; };
    j["timings_s"] = {{"load_terrain", seconds(Stage::terrain)},
                      {"control_mesh", seconds(Stage::control_mesh)},
                      {"fit", seconds(Stage::fit)},
                      {"fit_target", f.seconds_target},
                      {"fit_assemble", f.seconds_assemble},
                      {"fit_solve", f.seconds_solve},
                      {"tessellate", seconds(Stage::tessellation)}};
}

}  // namespace

std::string author_report_json(const Scene& scene, const PipelineProducts& products,
                               const std::array<StageRecord, stage_count>& stages)
{
    json j;
    j["fog"] = fog_spec_to_json(*scene.fog);
    surface_report(products, stages, j);
    j["optics"] = optics(scene.medium);
    if (products.placed && scene.fog->placement)
        j["placement"] = placement(scene, *products.placed);
    // The keys the scene left out and the pipeline derived from the terrain (scene_defaults.hpp).
    json derived = json::object();
    if (products.derived)
        for (const DerivedValue& v : products.derived->values)
            derived[v.key] = {{"value", v.value}, {"reason", v.reason}};
    j["derived"] = derived;
    return j.dump(2) + "\n";
}

std::vector<std::pair<std::string, std::string>> optics_metadata(const MediumOptions& m)
{
    const EngineFog e = engine_fog(m.extinction);
    auto num = [](double v) {
        char s[64];
        std::snprintf(s, sizeof s, "%.6g", v);
        return std::string(s);
    };
    return {{"KIRI_EXTINCTION_PER_M", num(m.extinction)},
            {"KIRI_VISIBILITY_M", num(visibility_from_extinction(m.extinction))},
            {"KIRI_ALBEDO", num(m.albedo)},
            {"KIRI_ANISOTROPY_G", num(m.anisotropy)},
            {"HDRP_FOG_ATTENUATION_DISTANCE_M", num(e.hdrp_attenuation_distance_m)},
            {"UNREAL_EXPONENTIAL_HEIGHT_FOG_DENSITY", num(e.unreal_fog_density)},
            {"GODOT_FOG_DENSITY", num(e.godot_density)}};
}

}  // namespace kiri::geometry
