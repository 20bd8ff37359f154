#include <algorithm>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/scene/fog_spec.hpp"

namespace kiri::geometry {
namespace {
// A spec whose fog the terrain places, not yet placed: placed here (callers that keep the
// PlacedFog, like author_scene_fog, place it once and pass the placed spec).
FogSpec resolve(const Terrain& terrain, const FogSpec& spec, const std::string& label)
{
    if (!spec.placement || !spec.footprint.polygon.empty())
        return spec;
    return placed_fog_spec(spec, place_fog(terrain, *spec.placement, spec.patch_size, label));
}
}  // namespace

FogSpec placed_fog_spec(const FogSpec& spec, const PlacedFog& placed)
{
    FogSpec s = spec;
    s.footprint = placed.outline.footprint;
    s.fit.mode = FitMode::lake;
    s.fit.altitude = placed.top;
    s.fit.altitude_grid = placed.flat ? nullptr : placed.top_grid;
    s.fit.thickness = std::max(1.0, placed.figures.max_thickness);
    return s;
}

Footprint fog_footprint(const Terrain& terrain, const FogSpec& spec, const std::string& label)
{
    if (!spec.footprint.polygon.empty())
        return spec.footprint;
    if (spec.placement)
        return resolve(terrain, spec, label).footprint;
    const Heightfield& hf = terrain.heightfield();
    const double m = spec.margin;
    if (!(2.0 * m < hf.x_max() - hf.x0 && 2.0 * m < hf.y_max() - hf.y0))
        throw InputError(label, "/fog/margin", "leaves no footprint inside the terrain");
    return rectangle_footprint({hf.x0 + m, hf.y0 + m}, {hf.x_max() - m, hf.y_max() - m});
}

BaseSurface fog_control_surface(const Terrain& terrain, const FogSpec& spec, const std::string& label)
{
    ControlMeshOptions cmo;
    cmo.patch_size = spec.patch_size;
    return BaseSurface(build_control_mesh(fog_footprint(terrain, spec, label), terrain, cmo, label), spec.surface);
}

FitReport fit_fog_surface(BaseSurface& surface, const Terrain& terrain, const FogSpec& spec, const std::string& label)
{
    try {
        return surface.fit(terrain, resolve(terrain, spec, label).fit);
    } catch (const InputError& e) {
        if (!e.file().empty())
            throw;
        throw InputError(label, e.field().empty() ? "/fog" : "/fog/" + e.field(), e.reason());
    }
}

}  // namespace kiri::geometry
