#include "kiri/geometry/fog/footprint.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "kiri/geometry/core/error.hpp"

namespace kiri::geometry {
namespace {

std::string fmt(glm::dvec2 p)
{
    std::ostringstream s;
    s.precision(10);
    s << "(" << p.x << ", " << p.y << ")";
    return s.str();
}

double cross(glm::dvec2 a, glm::dvec2 b) { return a.x * b.y - a.y * b.x; }

double signed_area(const std::vector<glm::dvec2>& p)
{
    double a = 0.0;
    for (std::size_t i = 0, n = p.size(); i < n; ++i)
        a += cross(p[i], p[(i + 1) % n]);
    return 0.5 * a;
}

// Orientation with a tolerance relative to the segment lengths, so that nearly collinear
// touching edges count as touching.
int orient(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, double eps)
{
    const double v = cross(b - a, c - a);
    return v > eps ? 1 : (v < -eps ? -1 : 0);
}

bool on_segment(glm::dvec2 a, glm::dvec2 b, glm::dvec2 p)
{
    return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
        p.y <= std::max(a.y, b.y);
}

bool segments_meet(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, glm::dvec2 d, double eps)
{
    const int o1 = orient(a, b, c, eps), o2 = orient(a, b, d, eps);
    const int o3 = orient(c, d, a, eps), o4 = orient(c, d, b, eps);
    if (o1 != o2 && o3 != o4 && o1 * o2 <= 0 && o3 * o4 <= 0 && (o1 || o2) && (o3 || o4))
        return true;
    return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) || (o3 == 0 && on_segment(c, d, a)) ||
        (o4 == 0 && on_segment(c, d, b));
}

bool inside_polygon(const std::vector<glm::dvec2>& p, glm::dvec2 q)
{
    bool in = false;
    for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
        if ((p[i].y > q.y) != (p[j].y > q.y) && q.x < (p[j].x - p[i].x) * (q.y - p[i].y) / (p[j].y - p[i].y) + p[i].x)
            in = !in;
    }
    return in;
}

glm::dvec2 closest_on_border(const std::vector<std::vector<glm::dvec2>>& polys, glm::dvec2 q)
{
    glm::dvec2 best = polys[0][0];
    double best_d = std::numeric_limits<double>::infinity();
    for (const auto& p : polys) {
        for (std::size_t i = 0, n = p.size(); i < n; ++i) {
            const glm::dvec2 a = p[i], b = p[(i + 1) % n], ab = b - a;
            const double t = std::clamp(glm::dot(q - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
            const glm::dvec2 c = a + t * ab;
            const double d = glm::dot(q - c, q - c);
            if (d < best_d) {
                best_d = d;
                best = c;
            }
        }
    }
    return best;
}

}  // namespace

Footprint rectangle_footprint(glm::dvec2 min, glm::dvec2 max)
{
    return {{{min.x, min.y}, {max.x, min.y}, {max.x, max.y}, {min.x, max.y}}};
}

namespace {

void validate_polygon(const std::vector<glm::dvec2>& p, const std::string& label, const std::string& which)
{
    const std::size_t n = p.size();
    if (n < 3)
        throw InputError(label, "footprint", which + "a polygon needs at least 3 vertices, got " + std::to_string(n));
    double extent = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        if (!std::isfinite(p[i].x) || !std::isfinite(p[i].y))
            throw InputError(label, "footprint", which + "vertex " + std::to_string(i) + " is not finite");
        extent = std::max({extent, std::abs(p[i].x - p[0].x), std::abs(p[i].y - p[0].y)});
    }
    for (std::size_t i = 0; i < n; ++i)
        if (p[i] == p[(i + 1) % n])
            throw InputError(label, "footprint",
                             which + "vertices " + std::to_string(i) + " and " + std::to_string((i + 1) % n) +
                                 " coincide at " + fmt(p[i]));
    const double area = std::abs(signed_area(p));
    if (!(area > 1e-12 * extent * extent) || extent == 0.0)
        throw InputError(label, "footprint", which + "the polygon has no area (degenerate)");
    const double eps = 1e-12 * extent * extent;
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j) {
            const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
            const glm::dvec2 a = p[i], b = p[(i + 1) % n], c = p[j], d = p[(j + 1) % n];
            if (adjacent) {
                // Neighbours share one vertex; they must not fold back onto each other.
                const glm::dvec2 shared = j == i + 1 ? b : a;
                const glm::dvec2 u = (j == i + 1 ? a : b) - shared, v = (j == i + 1 ? d : c) - shared;
                if (std::abs(cross(u, v)) <= eps && glm::dot(u, v) > 0.0)
                    throw InputError(label, "footprint",
                                     which + "edges " + std::to_string(i) + " and " + std::to_string(j) +
                                         " overlap (the polygon folds back at " + fmt(shared) + ")");
                continue;
            }
            // Far apart in y: cannot meet (cheap test first; long traced outlines are common).
            if (std::max(a.y, b.y) < std::min(c.y, d.y) || std::max(c.y, d.y) < std::min(a.y, b.y))
                continue;
            if (segments_meet(a, b, c, d, eps))
                throw InputError(label, "footprint",
                                 which + "edges " + std::to_string(i) + " and " + std::to_string(j) +
                                     " intersect: the polygon must be simple");
        }
}

struct Box {
    glm::dvec2 lo, hi;
};
Box box_of(const std::vector<glm::dvec2>& p)
{
    Box b{p[0], p[0]};
    for (const auto& q : p) {
        b.lo = glm::min(b.lo, q);
        b.hi = glm::max(b.hi, q);
    }
    return b;
}

// Two simple polygons must neither cross, touch nor nest.
void check_apart(const std::vector<glm::dvec2>& p, const std::vector<glm::dvec2>& q, std::size_t ip, std::size_t iq,
                 const std::string& label)
{
    const Box a = box_of(p), b = box_of(q);
    if (a.hi.x < b.lo.x || b.hi.x < a.lo.x || a.hi.y < b.lo.y || b.hi.y < a.lo.y)
        return;
    const double extent = std::max({a.hi.x - a.lo.x, a.hi.y - a.lo.y, b.hi.x - b.lo.x, b.hi.y - b.lo.y});
    const double eps = 1e-12 * extent * extent;
    const std::string which = "polygons " + std::to_string(ip) + " and " + std::to_string(iq);
    for (std::size_t i = 0; i < p.size(); ++i) {
        const glm::dvec2 s0 = p[i], s1 = p[(i + 1) % p.size()];
        if (std::max(s0.x, s1.x) < b.lo.x || std::min(s0.x, s1.x) > b.hi.x || std::max(s0.y, s1.y) < b.lo.y ||
            std::min(s0.y, s1.y) > b.hi.y)
            continue;
        for (std::size_t j = 0; j < q.size(); ++j)
            if (segments_meet(s0, s1, q[j], q[(j + 1) % q.size()], eps))
                throw InputError(label, "footprint",
                                 which + " meet (edges " + std::to_string(i) + " and " + std::to_string(j) +
                                     "): the polygons must be apart");
    }
    if (inside_polygon(p, q[0]) || inside_polygon(q, p[0]))
        throw InputError(label, "footprint", which + ": one lies inside the other");
}

}  // namespace

std::vector<std::vector<glm::dvec2>> footprint_polygons(const Footprint& footprint)
{
    std::vector<std::vector<glm::dvec2>> all;
    if (!footprint.polygon.empty())
        all.push_back(footprint.polygon);
    for (const auto& p : footprint.more)
        if (!p.empty())
            all.push_back(p);
    return all;
}

void validate_footprint(const Footprint& footprint, const std::string& label)
{
    const auto polys = footprint_polygons(footprint);
    if (polys.empty())
        validate_polygon(footprint.polygon, label, "");
    for (std::size_t k = 0; k < polys.size(); ++k)
        validate_polygon(polys[k], label, polys.size() > 1 ? "polygon " + std::to_string(k) + ": " : "");
    for (std::size_t a = 0; a < polys.size(); ++a)
        for (std::size_t b = a + 1; b < polys.size(); ++b)
            check_apart(polys[a], polys[b], a, b, label);
}

ControlMesh build_control_mesh(const Footprint& footprint, const Terrain& terrain, const ControlMeshOptions& options,
                               const std::string& label)
{
    validate_footprint(footprint, label);
    const double h = options.patch_size;
    if (!(h > 0.0) || !std::isfinite(h))
        throw InputError(label, "patch_size", "must be a positive number of metres");
    std::vector<std::vector<glm::dvec2>> polys = footprint_polygons(footprint);
    for (auto& poly : polys)
        if (signed_area(poly) < 0.0)
            std::reverse(poly.begin(), poly.end());

    const Heightfield& hf = terrain.heightfield();
    glm::dvec2 lo = polys[0][0], hi = polys[0][0];
    for (const auto& poly : polys)
        for (const auto& q : poly) {
            lo = glm::min(lo, q);
            hi = glm::max(hi, q);
        }
    const double tol = 1e-9 * std::max({1.0, std::abs(hf.x0), std::abs(hf.y0), hi.x - lo.x, hi.y - lo.y});
    for (std::size_t k = 0; k < polys.size(); ++k)
        for (std::size_t i = 0; i < polys[k].size(); ++i) {
            const glm::dvec2 q = polys[k][i];
            if (q.x < hf.x0 - tol || q.x > hf.x_max() + tol || q.y < hf.y0 - tol || q.y > hf.y_max() + tol) {
                std::ostringstream s;
                s.precision(10);
                s << (polys.size() > 1 ? "polygon " + std::to_string(k) + ": " : "") << "vertex " << i << " " << fmt(q)
                  << " lies outside the terrain [" << hf.x0 << ", " << hf.x_max() << "] x [" << hf.y0 << ", "
                  << hf.y_max() << "] (footprints are not clipped)";
                throw InputError(label, "footprint", s.str());
            }
        }
    auto inside_any = [&](glm::dvec2 q) {
        for (const auto& poly : polys)
            if (inside_polygon(poly, q))
                return true;
        return false;
    };

    const glm::dvec2 centre = 0.5 * (lo + hi);
    const double cells_x = std::max(1.0, std::ceil((hi.x - lo.x) / h - 1e-9));
    const double cells_y = std::max(1.0, std::ceil((hi.y - lo.y) / h - 1e-9));
    if (cells_x * cells_y > double(options.max_faces))
        throw LimitError(label, "patch_size",
                         "the footprint needs up to " + std::to_string(static_cast<long long>(cells_x * cells_y)) +
                             " patches, above the limit of " + std::to_string(options.max_faces));
    const int nx = int(cells_x), ny = int(cells_y);
    const glm::dvec2 start = centre - 0.5 * h * glm::dvec2(nx, ny);
    auto corner = [&](int i, int j) { return start + h * glm::dvec2(i, j); };

    std::vector<std::uint8_t> keep(std::size_t(nx) * ny, 0);
    auto kept = [&](int i, int j) { return i >= 0 && j >= 0 && i < nx && j < ny && keep[std::size_t(j) * nx + i]; };
    bool any = false;
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
            if (inside_any(corner(i, j) + glm::dvec2(0.5 * h))) {
                keep[std::size_t(j) * nx + i] = 1;
                any = true;
            }
    if (!any) {
        // Smaller than a patch (or thinner than one): the cell under the bounding-box centre.
        const int i = std::clamp(int((centre.x - start.x) / h), 0, nx - 1);
        const int j = std::clamp(int((centre.y - start.y) / h), 0, ny - 1);
        keep[std::size_t(j) * nx + i] = 1;
    }
    // Cells meeting at a single grid vertex make it non-manifold: add a cell between them.
    for (bool changed = true; changed;) {
        changed = false;
        for (int j = 1; j < ny; ++j)
            for (int i = 1; i < nx; ++i) {
                const bool a = kept(i - 1, j - 1), b = kept(i, j - 1), c = kept(i - 1, j), d = kept(i, j);
                if ((a && d && !b && !c) || (b && c && !a && !d)) {
                    keep[std::size_t(j - 1) * nx + i - (a ? 0 : 1)] = 1;
                    changed = true;
                }
            }
    }

    ControlMesh out;
    out.patch_size = h;
    out.origin = centre;
    out.grid_origin = start;
    std::vector<int> vid(std::size_t(nx + 1) * (ny + 1), -1);
    auto vertex = [&](int i, int j) {
        int& v = vid[std::size_t(j) * (nx + 1) + i];
        if (v < 0) {
            const glm::dvec2 q = corner(i, j);
            v = out.mesh.add_vertex(PolyMesh::Point(q.x, q.y, 0.0)).idx();
            out.grid.emplace_back(i, j);
        }
        return PolyMesh::VertexHandle(v);
    };
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
            if (kept(i, j))
                out.mesh.add_face({vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1), vertex(i, j + 1)});

    const int nv = out.num_vertices();
    std::vector<glm::dvec2> rest(nv), target(nv);
    std::vector<std::uint8_t> boundary(nv, 0), moved(nv, 0), corner_of(nv, 0);
    for (int v = 0; v < nv; ++v) {
        const auto p = out.mesh.point(PolyMesh::VertexHandle(v));
        rest[v] = target[v] = {p[0], p[1]};
        boundary[v] = out.mesh.is_boundary(PolyMesh::VertexHandle(v));
        out.boundary_vertices += boundary[v];
    }
    if (options.conform_to_border) {
        // Polygon corners first (they carry the shape), each to the nearest free boundary vertex.
        for (const auto& poly : polys) {
            for (const auto& c : poly) {
                int best = -1;
                double best_d = 1.5 * h;
                for (int v = 0; v < nv; ++v)
                    if (boundary[v] && !moved[v] && glm::length(rest[v] - c) < best_d) {
                        best_d = glm::length(rest[v] - c);
                        best = v;
                    }
                if (best >= 0) {
                    target[best] = c;
                    moved[best] = 1;
                    corner_of[best] = 1;
                }
            }
        }
        for (int v = 0; v < nv; ++v)
            if (boundary[v] && !moved[v]) {
                target[v] = closest_on_border(polys, rest[v]);
                moved[v] = 1;
            }
        // Back off where a quad would fold or collapse: halve the moves of its vertices.
        std::vector<double> t(nv, 1.0);
        auto pos = [&](int v) { return rest[v] + t[v] * (target[v] - rest[v]); };
        for (int round = 0; round < 12; ++round) {
            bool bad_any = false;
            for (auto f : out.mesh.faces()) {
                int q[4], k = 0;
                for (auto v : out.mesh.fv_range(f))
                    q[k++] = v.idx();
                bool ok = true;
                for (int c = 0; c < 4; ++c) {
                    const glm::dvec2 a = pos(q[c]), b = pos(q[(c + 1) % 4]), d = pos(q[(c + 3) % 4]);
                    // Convex with corner angles of at least ~3 degrees, whatever the quad's size.
                    const double lb = glm::length(b - a), ld = glm::length(d - a);
                    if (!(lb > 1e-9 * h && ld > 1e-9 * h) || cross(b - a, d - a) < 0.05 * lb * ld)
                        ok = false;
                }
                if (!ok) {
                    // A staircase's outer corner (a vertex of one quad only) snapped onto a
                    // straight border makes its quad a triangle: give way there first, then
                    // at the other moved vertices, the polygon's corners last.
                    bad_any = true;
                    int level = 2;
                    for (int c = 0; c < 4; ++c)
                        if (t[q[c]] > 0.0)
                            level = std::min(level,
                                             corner_of[q[c]]                                           ? 2
                                                 : out.mesh.valence(PolyMesh::VertexHandle(q[c])) == 2 ? 0
                                                                                                       : 1);
                    for (int c = 0; c < 4; ++c) {
                        const int l = corner_of[q[c]] ? 2 : out.mesh.valence(PolyMesh::VertexHandle(q[c])) == 2 ? 0 : 1;
                        if (l == level || round == 11)
                            t[q[c]] = round >= 9 ? 0.0 : 0.5 * t[q[c]];
                    }
                }
            }
            if (!bad_any)
                break;
        }
        for (int v = 0; v < nv; ++v) {
            const glm::dvec2 p = pos(v);
            out.mesh.set_point(PolyMesh::VertexHandle(v), PolyMesh::Point(p.x, p.y, 0.0));
            out.snapped_vertices += boundary[v] && t[v] == 1.0;
        }
    }
    for (auto v : out.mesh.vertices()) {
        auto p = out.mesh.point(v);
        p[2] = terrain.height(p[0], p[1]);
        out.mesh.set_point(v, p);
    }
    return out;
}

}  // namespace kiri::geometry
