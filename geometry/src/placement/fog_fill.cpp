#include "kiri/geometry/placement/fog_fill.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "kiri/geometry/core/error.hpp"
#include "placement/radix_heap.hpp"

namespace kiri::geometry {
namespace {

using detail::FloodItem;
using detail::key_value;
using detail::order_key;
using detail::RadixHeap;

std::string num(double v)
{
    std::ostringstream s;
    s.precision(10);
    s << v;
    return s.str();
}

bool has_mask(const Heightfield& hf) { return hf.valid.size() == hf.size(); }
bool valid_cell(const Heightfield& hf, std::size_t k) { return !has_mask(hf) || hf.valid[k]; }

constexpr int kDi[8] = {1, -1, 0, 0, 1, -1, 1, -1};
constexpr int kDj[8] = {0, 0, 1, -1, 1, 1, -1, -1};

// Cells handed to the flood before it starts: each is queued and enters the heap at its own
// level (ground + lift), as the saddle of its own path.
struct FloodStart {
    std::vector<std::uint8_t> queued;
    RadixHeap heap;
};

FloodStart start_at(const Heightfield& hf, const std::vector<std::uint32_t>& seeds, double lift)
{
    FloodStart s{std::vector<std::uint8_t>(hf.size(), 0), {}};
    for (std::uint32_t c : seeds) {
        s.queued[c] = 1;
        s.heap.push({order_key(hf.z[c] + lift), c, c});
    }
    return s;
}

// The priority-flood itself. Every queued cell has its own level; a popped cell hands its level
// (or its neighbour's ground, if higher) to each unqueued valid neighbour. `visit` sees the
// cells in non-decreasing level order and returns false to stop.
template <class Visit>
void flood(const Heightfield& hf, FloodStart& start, double lift, Visit&& visit)
{
    const int nx = hf.nx, ny = hf.ny;
    std::vector<std::uint8_t>& queued = start.queued;
    RadixHeap& heap = start.heap;
    // Cells reached at the current level without climbing (pits and plateaus under it) skip the
    // heap: their key is the smallest one, so a plain queue keeps the order ([Barnes14],
    // "Priority-Flood+epsilon" / improved priority-flood).
    std::vector<FloodItem> pit;
    std::size_t pit_head = 0;
    while (pit_head < pit.size() || !heap.empty()) {
        FloodItem it;
        if (pit_head < pit.size()) {
            it = pit[pit_head++];
            if (pit_head == pit.size()) {
                pit.clear();
                pit_head = 0;
            }
        } else {
            it = heap.pop();
        }
        if (!visit(it))
            return;
        const int i = int(it.cell % std::uint32_t(nx)), j = int(it.cell / std::uint32_t(nx));
        for (int d = 0; d < 8; ++d) {
            const int a = i + kDi[d], b = j + kDj[d];
            if (a < 0 || b < 0 || a >= nx || b >= ny)
                continue;
            const std::uint32_t n = std::uint32_t(b) * std::uint32_t(nx) + std::uint32_t(a);
            if (queued[n] || !valid_cell(hf, n))
                continue;
            queued[n] = 1;
            const std::uint64_t own = order_key(hf.z[n] + lift);
            if (own > it.key)
                heap.push({own, n, n});
            else
                pit.push_back({it.key, n, it.saddle});
        }
    }
}

void check_grid(const Heightfield& hf, const std::string& label)
{
    if (hf.nx < 1 || hf.ny < 1 || hf.size() != std::size_t(hf.nx) * std::size_t(hf.ny))
        throw InputError(label, "terrain", "empty or inconsistent heightfield");
    if (hf.size() >= (std::size_t(1) << 32))
        throw LimitError(label, "terrain", "more than 2^32 cells");
}

}  // namespace

std::vector<std::uint32_t> seed_cells(const Heightfield& hf, const FillSeeds& seeds, const std::string& label)
{
    check_grid(hf, label);
    std::vector<std::uint32_t> out;
    if (seeds.all_basins) {
        for (std::size_t k = 0; k < hf.size(); ++k)
            if (valid_cell(hf, k))
                out.push_back(std::uint32_t(k));
        return out;
    }
    std::vector<std::uint8_t> taken(hf.size(), 0);
    const double tx = 0.5 * hf.dx + 1e-9 * std::max(1.0, std::abs(hf.x0)),
                 ty = 0.5 * hf.dy + 1e-9 * std::max(1.0, std::abs(hf.y0));
    for (std::size_t s = 0; s < seeds.points.size(); ++s) {
        const glm::dvec2 p = seeds.points[s];
        const std::string field = "seeds/" + std::to_string(s);
        if (!std::isfinite(p.x) || !std::isfinite(p.y))
            throw InputError(label, field, "the seed is not a finite point");
        // Each sample stands for the cell of dx x dy around it.
        if (p.x < hf.x0 - tx || p.x > hf.x_max() + tx || p.y < hf.y0 - ty || p.y > hf.y_max() + ty)
            throw InputError(label, field,
                             "seed (" + num(p.x) + ", " + num(p.y) + ") lies outside the terrain [" + num(hf.x0) +
                                 ", " + num(hf.x_max()) + "] x [" + num(hf.y0) + ", " + num(hf.y_max()) +
                                 "] (local metres)");
        const int i = std::clamp(int(std::lround((p.x - hf.x0) / hf.dx)), 0, hf.nx - 1);
        const int j = std::clamp(int(std::lround((p.y - hf.y0) / hf.dy)), 0, hf.ny - 1);
        const std::size_t k = std::size_t(j) * hf.nx + i;
        if (!valid_cell(hf, k))
            throw InputError(label, field,
                             "seed (" + num(p.x) + ", " + num(p.y) + ") lies on a nodata cell of the terrain");
        if (!taken[k]++)
            out.push_back(std::uint32_t(k));
    }
    if (!seeds.mask.empty()) {
        if (seeds.mask.size() != hf.size())
            throw InputError(label, "seeds/mask",
                             "the seed mask has " + std::to_string(seeds.mask.size()) + " cells, the terrain " +
                                 std::to_string(hf.nx) + " x " + std::to_string(hf.ny));
        for (std::size_t k = 0; k < hf.size(); ++k)
            if (seeds.mask[k] && valid_cell(hf, k) && !taken[k]++)
                out.push_back(std::uint32_t(k));
    }
    if (out.empty())
        throw InputError(label, "seeds", "no seed: give seed points, a seed mask with cells on data, or all basins");
    return out;
}

FogFill fill_fog(const Heightfield& hf, const FillOptions& o, const std::string& label)
{
    const double unit = o.message_scale > 0.0 && std::isfinite(o.message_scale) ? o.message_scale : 1.0;
    if (!std::isfinite(o.top))
        throw InputError(label, "top", "must be a finite altitude (metres)");
    if (!(o.min_thickness >= 0.0) || !std::isfinite(o.min_thickness))
        throw InputError(label, "min_thickness", "must be a finite number >= 0");
    if (!std::isfinite(o.max_thickness) || o.max_thickness < 0.0 ||
        (o.max_thickness > 0.0 && o.max_thickness <= o.min_thickness))
        throw InputError(label, "max_thickness",
                         "must be 0 (no limit) or larger than min_thickness (" + num(o.min_thickness / unit) +
                             " m), got " + num(o.max_thickness / unit));
    const std::vector<std::uint32_t> all = seed_cells(hf, o.seeds, label);
    // The flood runs on ground + min_thickness: a cell carries fog when that is below the top.
    const double lift = o.min_thickness;
    const std::uint64_t top_key = order_key(o.top);
    std::vector<std::uint32_t> seeds;
    double lowest = INFINITY;
    for (std::uint32_t s : all) {
        lowest = std::min(lowest, hf.z[s]);
        if (order_key(hf.z[s] + lift) < top_key)
            seeds.push_back(s);
    }
    if (seeds.empty())
        throw InputError(label, "top",
                         "the fog top " + num(o.top / unit) +
                             " m is at or below every seed (the lowest seed's ground is " + num(lowest / unit) + " m" +
                             (lift > 0.0 ? ", plus min_thickness " + num(lift / unit) + " m" : "") + "): no fog");

    FogFill f;
    f.nx = hf.nx;
    f.ny = hf.ny;
    f.top = o.top;
    f.mask.assign(hf.size(), 0);
    f.thickness.assign(hf.size(), 0.0);
    f.seed_cells = int(seeds.size());
    const double cell_area = hf.dx * hf.dy;
    double sum = 0.0;
    // The region: cells joined to a seed through cells whose ground + lift is below the top.
    // Those are exactly the cells the priority-flood would reach at a level below the top (a
    // level is the highest ground on the path), so a breadth-first search finds them in linear
    // time; only the search for the spill needs the flood's order. Its start is the region's
    // rim: the valid cells next to the region, all at or above the top.
    FloodStart rim{std::vector<std::uint8_t>(hf.size(), 0), {}};
    std::vector<std::uint32_t> queue = seeds;
    for (std::uint32_t s : seeds)
        rim.queued[s] = 1;
    const int nx = hf.nx, ny = hf.ny;
    for (std::size_t head = 0; head < queue.size(); ++head) {
        const std::uint32_t k = queue[head];
        f.mask[k] = 1;
        const double t = o.max_thickness > 0.0 ? std::min(o.top - hf.z[k], o.max_thickness) : o.top - hf.z[k];
        f.thickness[k] = t;
        sum += t;
        f.max_thickness = std::max(f.max_thickness, t);
        const int i = int(k % std::uint32_t(nx)), j = int(k / std::uint32_t(nx));
        f.touches_border = f.touches_border || i == 0 || j == 0 || i == nx - 1 || j == ny - 1;
        for (int d = 0; d < 8; ++d) {
            const int a = i + kDi[d], b = j + kDj[d];
            if (a < 0 || b < 0 || a >= nx || b >= ny)
                continue;
            const std::uint32_t n = std::uint32_t(b) * std::uint32_t(nx) + std::uint32_t(a);
            if (rim.queued[n] || !valid_cell(hf, n))
                continue;
            rim.queued[n] = 1;
            const std::uint64_t own = order_key(hf.z[n] + lift);
            if (own < top_key)
                queue.push_back(n);
            else if (!o.seeds.all_basins)
                rim.heap.push({own, n, n});
        }
    }
    f.cells = queue.size();
    // Past the top: the flood climbs over the lowest saddle; the first cell it meets whose own
    // ground is below the top lies in another basin, reached at this level.
    if (!o.seeds.all_basins)
        flood(hf, rim, lift, [&](const FloodItem& it) {
            if (order_key(hf.z[it.cell] + lift) >= top_key)
                return true;
            f.spills = true;
            f.spill_level = key_value(it.key);
            f.spill_point = {hf.x_of(int(it.saddle % std::uint32_t(nx))), hf.y_of(int(it.saddle / std::uint32_t(nx)))};
            return false;
        });
    f.area_m2 = double(f.cells) * cell_area;
    f.volume_m3 = sum * cell_area;
    f.mean_thickness = f.cells ? sum / double(f.cells) : 0.0;
    return f;
}

FloodLevels flood_levels(const Heightfield& hf, const FillSeeds& seeds, const std::string& label)
{
    const std::vector<std::uint32_t> s = seed_cells(hf, seeds, label);
    FloodLevels out;
    out.level.assign(hf.size(), 0.0);
    out.reached.assign(hf.size(), 0);
    FloodStart start = start_at(hf, s, 0.0);
    flood(hf, start, 0.0, [&](const FloodItem& it) {
        out.level[it.cell] = key_value(it.key);
        out.reached[it.cell] = 1;
        return true;
    });
    return out;
}

}  // namespace kiri::geometry
