#include <chrono>

#include "kiri/geometry/error.hpp"
#include "kiri/geometry/fog_spec.hpp"

namespace kiri::geometry {
namespace {
double since(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

AuthoredSurface author_base_surface(const Terrain& terrain, const FogSpec& spec, const std::string& label)
{
    auto t0 = std::chrono::steady_clock::now();
    Footprint fp = spec.footprint;
    if (fp.polygon.empty()) {
        const Heightfield& hf = terrain.heightfield();
        const double m = spec.margin;
        if (!(2.0 * m < hf.x_max() - hf.x0 && 2.0 * m < hf.y_max() - hf.y0))
            throw InputError(label, "/fog/margin", "leaves no footprint inside the terrain");
        fp = rectangle_footprint({hf.x0 + m, hf.y0 + m}, {hf.x_max() - m, hf.y_max() - m});
    }
    ControlMeshOptions cmo;
    cmo.patch_size = spec.patch_size;
    ControlMesh cm = build_control_mesh(fp, terrain, cmo, label);
    AuthoredSurface out{BaseSurface(std::move(cm), spec.surface), {}, {}};
    out.seconds_control_mesh = since(t0);
    t0 = std::chrono::steady_clock::now();
    try {
        out.fit = out.surface.fit(terrain, spec.fit);
    } catch (const InputError& e) {
        if (!e.file().empty())
            throw;
        throw InputError(label, e.field().empty() ? "/fog" : "/fog/" + e.field(), e.reason());
    }
    out.seconds_fit = since(t0);
    t0 = std::chrono::steady_clock::now();
    out.tessellation = tessellate(out.surface, spec.tessellation);
    out.seconds_tessellate = since(t0);
    return out;
}

}  // namespace kiri::geometry
