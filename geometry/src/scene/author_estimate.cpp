#include "kiri/geometry/scene/author_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/common.hpp>

#include "kiri/geometry/core/error.hpp"

namespace kiri::geometry {
namespace {

// Bytes per item, measured on the Jacksboro scenes (peak RSS against counts) and rounded up:
// an OpenMesh TriMesh in double with normals, texcoords and a property per vertex, its
// ~2 faces and ~3 edges; the fit's per-sample stencil rows; a layer vertex kept for export
// plus its share of the glTF buffer.
constexpr double terrain_cell_bytes = 420.0;  // heights, mask, target grids, mesh + AABB for export
constexpr double sample_bytes = 260.0;        // (face, u, v) + 16..20 stencil weights
constexpr double patch_bytes = 4096.0;        // per-face stencils, control mesh, normal equations
constexpr double tessellation_vertex_bytes = 260.0;
constexpr double layer_vertex_bytes = 96.0;  // LayerVertex (40) + glTF floats (28) + OBJ/PLY buffers
constexpr double mib = 1024.0 * 1024.0;

}  // namespace

std::string AuthorEstimate::summary() const
{
    char text[200];
    std::snprintf(text, sizeof text, "about %.0f MiB (terrain %.0f, fit %.0f, tessellation %.0f, layers %.0f)",
                  total_mib(), terrain_mib, fit_mib, tessellation_mib, layers_mib);
    return text;
}

AuthorEstimate estimate_author(const FogSpec& spec, const Heightfield& hf, int layers)
{
    AuthorEstimate e;
    double w = hf.x_max() - hf.x0, h = hf.y_max() - hf.y0;
    if (!spec.footprint.polygon.empty()) {
        glm::dvec2 lo = spec.footprint.polygon.front(), hi = lo;
        for (const auto& poly : footprint_polygons(spec.footprint))  // every polygon's box
            for (const glm::dvec2& p : poly) {
                lo = glm::min(lo, p);
                hi = glm::max(hi, p);
            }
        w = hi.x - lo.x;
        h = hi.y - lo.y;
    } else {
        w = std::max(w - 2.0 * spec.margin, 0.0);
        h = std::max(h - 2.0 * spec.margin, 0.0);
    }
    const double patch = spec.patch_size > 0.0 ? spec.patch_size : 1.0;
    e.patches = std::max(1.0, std::ceil(w / patch)) * std::max(1.0, std::ceil(h / patch));
    const double cells = double(hf.nx) * hf.ny;
    const double covered = std::min(cells, (w / hf.dx + 1.0) * (h / hf.dy + 1.0));
    e.samples = covered + e.patches * 16.0;
    const int level = spec.tessellation.tolerance > 0.0 ? spec.tessellation.max_level : spec.tessellation.level;
    e.tessellation_vertices = e.patches * double(level + 1) * double(level + 1);
    e.layer_vertices = e.tessellation_vertices * double(std::max(layers, 0) + 1);
    e.terrain_mib = cells * terrain_cell_bytes / mib;
    e.fit_mib = (e.samples * sample_bytes + e.patches * patch_bytes) / mib;
    e.tessellation_mib = e.tessellation_vertices * tessellation_vertex_bytes / mib;
    e.layers_mib = e.layer_vertices * layer_vertex_bytes / mib;
    return e;
}

void check_author_estimate(const AuthorEstimate& e, const std::string& label)
{
    if (e.total_mib() <= author_memory_limit_mib)
        return;
    const char* key = "/fog/tessellation/level";
    double largest = e.tessellation_mib;
    if (e.layers_mib > largest) {
        key = "/layers/count";
        largest = e.layers_mib;
    }
    if (e.fit_mib > largest) {
        key = "/fog/patch_size";
        largest = e.fit_mib;
    }
    if (e.terrain_mib > largest)
        key = "/terrain/path";
    char limit[64];
    std::snprintf(limit, sizeof limit, "; the limit is %.0f MiB", author_memory_limit_mib);
    throw LimitError(label, key, "authoring would need " + e.summary() + limit);
}

}  // namespace kiri::geometry
