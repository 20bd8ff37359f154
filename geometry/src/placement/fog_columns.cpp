#include "kiri/geometry/placement/fog_columns.hpp"

#include <algorithm>

#include "kiri/geometry/core/error.hpp"

namespace kiri::geometry {

FogColumns fill_columns(const Heightfield& hf, const FogFill& f)
{
    FogColumns c;
    c.nx = hf.nx;
    c.ny = hf.ny;
    c.mask = f.mask;
    c.bottom = hf.z;
    c.top = hf.z;
    for (std::size_t k = 0; k < hf.size(); ++k)
        if (f.mask[k]) {
            c.top[k] = f.top;
            c.bottom[k] = f.top - f.thickness[k];
        }
    return c;
}

FogColumns merge_columns(const FogColumns& a, const FogColumns& b)
{
    if (a.nx != b.nx || a.ny != b.ny)
        throw InputError("", "columns", "fog columns on different grids cannot be merged");
    FogColumns c = a;
    for (std::size_t k = 0; k < c.mask.size(); ++k) {
        if (!b.mask[k])
            continue;
        if (!a.mask[k]) {
            c.bottom[k] = b.bottom[k];
            c.top[k] = b.top[k];
        } else {
            c.bottom[k] = std::min(a.bottom[k], b.bottom[k]);
            c.top[k] = std::max(a.top[k], b.top[k]);
        }
        c.mask[k] = 1;
    }
    return c;
}

ColumnFigures column_figures(const Heightfield& hf, const FogColumns& c)
{
    ColumnFigures f;
    double sum = 0.0;
    bool first = true;
    for (std::size_t k = 0; k < c.mask.size(); ++k) {
        if (!c.mask[k])
            continue;
        const double t = c.top[k] - c.bottom[k];
        ++f.cells;
        sum += t;
        f.max_thickness = std::max(f.max_thickness, t);
        if (first) {
            f.top_min = f.top_max = c.top[k];
            f.bottom_min = f.bottom_max = c.bottom[k];
            first = false;
        }
        f.top_min = std::min(f.top_min, c.top[k]);
        f.top_max = std::max(f.top_max, c.top[k]);
        f.bottom_min = std::min(f.bottom_min, c.bottom[k]);
        f.bottom_max = std::max(f.bottom_max, c.bottom[k]);
    }
    const double cell = hf.dx * hf.dy;
    f.area_m2 = double(f.cells) * cell;
    f.volume_m3 = sum * cell;
    f.mean_thickness = f.cells ? sum / double(f.cells) : 0.0;
    return f;
}

}  // namespace kiri::geometry
