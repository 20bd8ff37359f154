// place_fog: fill regions -> merged columns -> flow -> burn-off -> outline and lake target.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/placement/fog_maps.hpp"
#include "kiri/geometry/placement/fog_placement.hpp"

namespace kiri::geometry {
namespace {

double since(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Runs f, renaming a relative InputError field "x" to "<prefix>/x" with label as the file.
template <class F>
auto scoped(const std::string& label, const std::string& prefix, F&& f)
{
    try {
        return f();
    } catch (const InputError& e) {
        if (!e.file().empty() && e.file() != label)
            throw;
        if (e.field().rfind('/', 0) == 0)
            throw InputError(label, e.field(), e.reason());
        throw InputError(label, prefix + (e.field().empty() ? "" : "/" + e.field()), e.reason());
    }
}

// Nearest fog cell's top for every cell (multi-source breadth-first, 8-neighbours).
std::vector<double> extend_tops(const FogColumns& c)
{
    std::vector<double> top = c.top;
    std::vector<std::uint8_t> known = c.mask;
    std::vector<std::uint32_t> front, next;
    for (std::size_t k = 0; k < known.size(); ++k)
        if (known[k])
            front.push_back(std::uint32_t(k));
    while (!front.empty()) {
        next.clear();
        for (std::uint32_t k : front) {
            const int i = int(k % std::uint32_t(c.nx)), j = int(k / std::uint32_t(c.nx));
            for (int b = std::max(0, j - 1); b <= std::min(c.ny - 1, j + 1); ++b)
                for (int a = std::max(0, i - 1); a <= std::min(c.nx - 1, i + 1); ++a) {
                    const std::size_t n = std::size_t(b) * c.nx + a;
                    if (!known[n]) {
                        known[n] = 1;
                        top[n] = top[k];
                        next.push_back(std::uint32_t(n));
                    }
                }
        }
        front.swap(next);
    }
    return top;
}

}  // namespace

double evaporation_depth_for(double extinction)
{
    const double lwc = extinction * 4.0 * 1e6 * 7e-6 / (3.0 * 2.0);  // g/m^3
    return lwc / (9.8e-3 * 0.45);
}

PlacedFog place_fog(const Terrain& terrain, const PlacementSpec& spec, double patch_size, const std::string& label)
{
    const Heightfield& hf = terrain.heightfield();
    if (spec.regions.empty())
        throw InputError(label, "/fog/fill", "needs at least one region (an object with a top and seeds)");
    PlacedFog out;
    std::vector<double> profile_bottom;  // per cell, the regions' blended medium bottom
    std::vector<std::uint8_t> profiled;
    for (std::size_t r = 0; r < spec.regions.size(); ++r) {
        const FillRegionSpec& region = spec.regions[r];
        const std::string prefix = spec.regions.size() > 1 ? "/fog/fill/" + std::to_string(r) : "/fog/fill";
        FillOptions fo;
        fo.top = region.top;
        fo.min_thickness = region.min_thickness;
        fo.max_thickness = region.max_thickness;
        fo.message_scale = spec.exaggeration;
        switch (region.seeds) {
        case SeedKind::points: fo.seeds.points = region.points; break;
        case SeedKind::all: fo.seeds.all_basins = true; break;
        case SeedKind::valleys: {
            const auto t0 = std::chrono::steady_clock::now();
            ValleyMap v = scoped(label, prefix, [&] { return analyse_valleys(hf, region.valleys); });
            out.seconds_valleys += since(t0);
            if (v.cells == 0)
                throw InputError(label, prefix + "/valleys/threshold",
                                 "no cell of the terrain is a valley at this threshold: lower it");
            fo.seeds.mask = v.mask;
            if (!out.valleys)
                out.valleys = std::move(v);
            break;
        }
        case SeedKind::mask: fo.seeds.mask = read_mask(region.mask_path, hf, label, prefix + "/seeds/mask"); break;
        }
        auto t0 = std::chrono::steady_clock::now();
        FogFill fill = scoped(label, prefix, [&] { return fill_fog(hf, fo); });
        out.seconds_fill += since(t0);
        if (region.seeds == SeedKind::points && !out.flood) {
            t0 = std::chrono::steady_clock::now();
            out.flood = flood_levels(hf, fo.seeds);
            out.seconds_flood_levels = since(t0);
        }
        const FogColumns cols = fill_columns(hf, fill);
        // The medium's bottom: between each column's own bottom (profile 0) and the region's
        // lowest bottom (profile 1).
        double lowest = region.top;
        for (std::size_t k = 0; k < cols.mask.size(); ++k)
            if (cols.mask[k])
                lowest = std::min(lowest, cols.bottom[k]);
        if (r == 0) {
            out.columns = cols;
            profile_bottom = hf.z;
            profiled.assign(hf.size(), 0);
        } else {
            out.columns = merge_columns(out.columns, cols);
        }
        for (std::size_t k = 0; k < cols.mask.size(); ++k)
            if (cols.mask[k]) {
                const double b = (1.0 - region.profile) * cols.bottom[k] + region.profile * lowest;
                profile_bottom[k] = profiled[k] ? std::min(profile_bottom[k], b) : b;
                profiled[k] = 1;
            }
        out.fills.push_back(std::move(fill));
    }
    out.flat = true;
    out.top = spec.regions[0].top;
    for (const FillRegionSpec& region : spec.regions)
        out.flat = out.flat && region.top == out.top;

    if (spec.flow) {
        const auto t0 = std::chrono::steady_clock::now();
        FlowReport rep;
        out.columns = scoped(label, "/fog", [&] { return flow_fog(hf, out.columns, *spec.flow, &rep); });
        out.flow = rep;
        out.flat = false;
        out.seconds_flow = since(t0);
    }
    if (spec.burn_off) {
        const auto t0 = std::chrono::steady_clock::now();
        BurnOffOptions bo = *spec.burn_off;
        if (!spec.latitude_given)
            bo.latitude = terrain_latitude(hf, bo.latitude);
        out.latitude = bo.latitude;
        BurnOffReport rep;
        out.columns = scoped(label, "/fog", [&] { return burn_off(hf, out.columns, bo, &rep); });
        out.burn_off = rep;
        out.seconds_burn_off = since(t0);
        bool any = false;
        for (std::uint8_t m : out.columns.mask)
            any = any || m;
        if (!any)
            throw InputError(label, "/fog/burn_off/time",
                             "the fog has burnt off completely by " + std::to_string(bo.time).substr(0, 5) +
                                 " h (lifted base " + std::to_string(int(std::lround(rep.lifted_base))) +
                                 " m): choose an earlier time");
    }
    bool any = false;
    for (std::uint8_t m : out.columns.mask)
        any = any || m;
    if (!any)
        throw InputError(label, "/fog/flow", "no fog is left after the flow");
    out.figures = column_figures(hf, out.columns);

    out.medium_bottom = hf.z;
    for (std::size_t k = 0; k < hf.size(); ++k)
        if (out.columns.mask[k])
            out.medium_bottom[k] = std::min(
                out.columns.bottom[k], profiled.empty() || !profiled[k] ? out.columns.bottom[k] : profile_bottom[k]);

    // The lake target and where the footprint may grow: ground the fog top passes under.
    std::vector<std::uint8_t> growable(hf.size(), 0);
    if (out.flat) {
        for (std::size_t k = 0; k < hf.size(); ++k)
            growable[k] = !out.columns.mask[k] && (hf.z[k] >= out.top || (!hf.valid.empty() && !hf.valid[k]));
    } else {
        const std::vector<double> reach = extend_tops(out.columns);
        auto grid = std::make_shared<Heightfield>(hf);
        for (std::size_t k = 0; k < hf.size(); ++k) {
            if (out.columns.mask[k]) {
                grid->z[k] = out.columns.top[k];
            } else {
                // Just under the ground: the fitted top stays hidden where there is no fog.
                grid->z[k] = std::min(reach[k], hf.z[k] - 1.0);
                growable[k] = 1;
            }
        }
        out.top_grid = std::move(grid);
        out.top = out.figures.top_max;
    }
    const auto t0 = std::chrono::steady_clock::now();
    OutlineOptions oo;
    oo.margin = spec.margin >= 0.0 ? spec.margin : patch_size;
    oo.tolerance = spec.tolerance > 0.0 ? spec.tolerance : 0.25 * patch_size;
    oo.min_area = spec.min_area;
    out.outline = scoped(label, "/fog/outline", [&] { return mask_outline(hf, out.columns.mask, growable, oo); });
    out.seconds_outline = since(t0);
    return out;
}

}  // namespace kiri::geometry
