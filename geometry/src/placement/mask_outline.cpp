#include "kiri/geometry/placement/mask_outline.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "kiri/geometry/core/error.hpp"

namespace kiri::geometry {
namespace {

using Ring = std::vector<glm::dvec2>;

// Grows the mask ring by ring into growable cells (8-neighbours), `steps` rings.
void grow(std::vector<std::uint8_t>& mask, const std::vector<std::uint8_t>& growable, int nx, int ny, int steps)
{
    std::vector<std::uint32_t> front;
    for (std::size_t k = 0; k < mask.size(); ++k)
        if (mask[k])
            front.push_back(std::uint32_t(k));
    std::vector<std::uint32_t> next;
    for (int s = 0; s < steps && !front.empty(); ++s) {
        next.clear();
        for (std::uint32_t k : front) {
            const int i = int(k % std::uint32_t(nx)), j = int(k / std::uint32_t(nx));
            for (int b = std::max(0, j - 1); b <= std::min(ny - 1, j + 1); ++b)
                for (int a = std::max(0, i - 1); a <= std::min(nx - 1, i + 1); ++a) {
                    const std::size_t n = std::size_t(b) * nx + a;
                    if (!mask[n] && growable[n]) {
                        mask[n] = 1;
                        next.push_back(std::uint32_t(n));
                    }
                }
        }
        front.swap(next);
    }
}

// Cells that touch only at a corner would pinch the traced outline into a non-simple polygon:
// the pair is joined through one of the two empty cells (the first, a fixed choice).
void close_diagonals(std::vector<std::uint8_t>& m, int nx, int ny)
{
    for (bool changed = true; changed;) {
        changed = false;
        for (int j = 0; j + 1 < ny; ++j)
            for (int i = 0; i + 1 < nx; ++i) {
                const std::size_t k = std::size_t(j) * nx + i;
                const bool a = m[k], b = m[k + 1], c = m[k + nx], d = m[k + nx + 1];
                if (a && d && !b && !c) {
                    m[k + 1] = 1;
                    changed = true;
                } else if (b && c && !a && !d) {
                    m[k] = 1;
                    changed = true;
                }
            }
    }
}

// 4-connected components: label per cell (0 = none), their first cell in raster order and size.
struct Components {
    std::vector<std::uint32_t> label;
    std::vector<std::uint32_t> first;
    std::vector<std::size_t> cells;
};

Components label_components(const std::vector<std::uint8_t>& m, int nx, int ny)
{
    Components c;
    c.label.assign(m.size(), 0);
    std::vector<std::uint32_t> stack;
    for (std::size_t k = 0; k < m.size(); ++k) {
        if (!m[k] || c.label[k])
            continue;
        const std::uint32_t id = std::uint32_t(c.first.size() + 1);
        c.first.push_back(std::uint32_t(k));
        std::size_t count = 0;
        c.label[k] = id;
        stack.assign(1, std::uint32_t(k));
        while (!stack.empty()) {
            const std::uint32_t q = stack.back();
            stack.pop_back();
            ++count;
            const int i = int(q % std::uint32_t(nx)), j = int(q / std::uint32_t(nx));
            const int ni[4] = {i + 1, i - 1, i, i}, nj[4] = {j, j, j + 1, j - 1};
            for (int d = 0; d < 4; ++d) {
                if (ni[d] < 0 || nj[d] < 0 || ni[d] >= nx || nj[d] >= ny)
                    continue;
                const std::size_t n = std::size_t(nj[d]) * nx + ni[d];
                if (m[n] && !c.label[n]) {
                    c.label[n] = id;
                    stack.push_back(std::uint32_t(n));
                }
            }
        }
        c.cells.push_back(count);
    }
    return c;
}

// The outer border of component `id`, counter-clockwise along cell edges, as corner indices
// (corner (X, Y) is the south-west corner of cell (X, Y)); one vertex per change of direction.
std::vector<glm::ivec2> trace(const Components& c, std::uint32_t id, int nx, int ny)
{
    auto in = [&](int i, int j) {
        return i >= 0 && j >= 0 && i < nx && j < ny && c.label[std::size_t(j) * nx + i] == id;
    };
    // Headings E, N, W, S; the cells left and right of the edge leaving corner (X, Y).
    const int dx[4] = {1, 0, -1, 0}, dy[4] = {0, 1, 0, -1};
    const int li[4] = {0, -1, -1, 0}, lj[4] = {0, 0, -1, -1};
    const int ri[4] = {0, 0, -1, -1}, rj[4] = {-1, 0, 0, -1};
    auto boundary_edge = [&](int X, int Y, int h) { return in(X + li[h], Y + lj[h]) && !in(X + ri[h], Y + rj[h]); };

    const std::uint32_t k0 = c.first[id - 1];
    const glm::ivec2 start(int(k0 % std::uint32_t(nx)), int(k0 / std::uint32_t(nx)));
    // The start is the south-west corner of the component's first cell in raster order: the
    // cells west and south of it are outside, so it is a convex corner of the outer border.
    std::vector<glm::ivec2> out{start};
    glm::ivec2 p = start + glm::ivec2(1, 0);
    int h = 0;
    while (p != start) {
        // Right turn first, then straight, then left: with diagonal contacts closed exactly one
        // of them is a border edge with the component on its left.
        int next = h;
        for (int turn : {3, 0, 1})
            if (boundary_edge(p.x, p.y, (h + turn) % 4)) {
                next = (h + turn) % 4;
                break;
            }
        if (next != h)
            out.push_back(p);
        h = next;
        p += glm::ivec2(dx[h], dy[h]);
    }
    return out;
}

double distance_to_segment(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b)
{
    const glm::dvec2 ab = b - a;
    const double len2 = glm::dot(ab, ab);
    const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
    return glm::length(p - (a + t * ab));
}

void douglas_peucker(const Ring& r, std::size_t a, std::size_t b, double tol, std::vector<std::uint8_t>& keep)
{
    // Iterative (an outline can have tens of thousands of vertices).
    std::vector<std::pair<std::size_t, std::size_t>> todo{{a, b}};
    while (!todo.empty()) {
        const auto [s, e] = todo.back();
        todo.pop_back();
        double worst = -1.0;
        std::size_t at = s;
        for (std::size_t k = s + 1; k < e; ++k) {
            const double d = distance_to_segment(r[k], r[s], r[e % r.size()]);
            if (d > worst) {
                worst = d;
                at = k;
            }
        }
        if (worst > tol) {
            keep[at] = 1;
            todo.push_back({s, at});
            todo.push_back({at, e});
        }
    }
}

Ring simplify(const Ring& r, double tol)
{
    if (tol <= 0.0 || r.size() <= 4)
        return r;
    // Split the closed ring at vertex 0 and the vertex farthest from it.
    std::size_t far = 0;
    double far_d = -1.0;
    for (std::size_t k = 1; k < r.size(); ++k)
        if (glm::length(r[k] - r[0]) > far_d) {
            far_d = glm::length(r[k] - r[0]);
            far = k;
        }
    std::vector<std::uint8_t> keep(r.size(), 0);
    keep[0] = keep[far] = 1;
    douglas_peucker(r, 0, far, tol, keep);
    douglas_peucker(r, far, r.size(), tol, keep);
    Ring out;
    for (std::size_t k = 0; k < r.size(); ++k)
        if (keep[k])
            out.push_back(r[k]);
    return out;
}

// Drops repeated and collinear vertices (clamping to the extent makes some).
Ring tidy(const Ring& r)
{
    Ring out;
    for (const glm::dvec2& q : r)
        if (out.empty() || q != out.back())
            out.push_back(q);
    while (out.size() > 1 && out.front() == out.back())
        out.pop_back();
    for (bool changed = true; changed && out.size() > 3;) {
        changed = false;
        for (std::size_t k = 0; k < out.size() && out.size() > 3; ++k) {
            const glm::dvec2 a = out[(k + out.size() - 1) % out.size()], b = out[k], c = out[(k + 1) % out.size()];
            const glm::dvec2 u = b - a, v = c - b;
            if (u.x * v.y - u.y * v.x == 0.0) {
                out.erase(out.begin() + std::ptrdiff_t(k));
                changed = true;
            }
        }
    }
    return out;
}

bool inside_ring(const Ring& p, glm::dvec2 q)
{
    bool in = false;
    for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++)
        if ((p[i].y > q.y) != (p[j].y > q.y) && q.x < (p[j].x - p[i].x) * (q.y - p[i].y) / (p[j].y - p[i].y) + p[i].x)
            in = !in;
    return in;
}

// Whether the polygons hold every required cell centre and no forbidden one (scanline fill of
// the cell centres; cells on the grid's border are left out: the clamped outline runs through
// them). Simplifying may cut a corner or take in a little ground on either side.
bool respects(const Footprint& f, const Heightfield& g, const std::vector<std::uint8_t>& required,
              const std::vector<std::uint8_t>& allowed)
{
    const int nx = g.nx, ny = g.ny;
    std::vector<std::vector<double>> cross(static_cast<std::size_t>(ny));
    for (const Ring& r : footprint_polygons(f))
        for (std::size_t e = 0; e < r.size(); ++e) {
            const glm::dvec2 a = r[e], b = r[(e + 1) % r.size()];
            if (a.y == b.y)
                continue;
            const double lo = std::min(a.y, b.y), hi = std::max(a.y, b.y);
            const int j0 = std::max(0, int(std::ceil((lo - g.y0) / g.dy))),
                      j1 = std::min(ny - 1, int(std::floor((hi - g.y0) / g.dy)));
            for (int j = j0; j <= j1; ++j) {
                const double y = g.y_of(j);
                if (y < lo || y >= hi)  // half-open: a vertex on the line counts once
                    continue;
                cross[std::size_t(j)].push_back(a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y));
            }
        }
    for (int j = 1; j + 1 < ny; ++j) {
        auto& xs = cross[std::size_t(j)];
        std::sort(xs.begin(), xs.end());
        std::size_t next = 0;
        bool in = false;
        for (int i = 0; i < nx; ++i) {
            const double x = g.x_of(i);
            while (next < xs.size() && xs[next] < x) {
                in = !in;
                ++next;
            }
            if (i == 0 || i == nx - 1)
                continue;
            const std::size_t k = std::size_t(j) * nx + i;
            if (in ? !allowed[k] : required[k] != 0)
                return false;
        }
    }
    return true;
}

}  // namespace

MaskOutline mask_outline(const Heightfield& g, std::vector<std::uint8_t> mask,
                         const std::vector<std::uint8_t>& growable, const OutlineOptions& o, const std::string& label)
{
    const int nx = g.nx, ny = g.ny;
    if (mask.size() != g.size() || (!growable.empty() && growable.size() != g.size()))
        throw InputError(
            label, "mask",
            "the mask does not have the terrain's " + std::to_string(nx) + " x " + std::to_string(ny) + " cells");
    if (!(o.margin >= 0.0) || !(o.tolerance >= 0.0) || !(o.min_area >= 0.0) ||
        !std::isfinite(o.margin + o.tolerance + o.min_area))
        throw InputError(label, "mask", "margin, tolerance and min_area must be finite and >= 0");
    const std::vector<std::uint8_t> required = mask;
    if (o.margin > 0.0 && !growable.empty())
        grow(mask, growable, nx, ny, int(std::ceil(o.margin / std::min(g.dx, g.dy) - 1e-9)));
    close_diagonals(mask, nx, ny);
    std::vector<std::uint8_t> allowed = mask;
    for (std::size_t k = 0; k < allowed.size() && !growable.empty(); ++k)
        allowed[k] = allowed[k] || growable[k];
    const Components comps = label_components(mask, nx, ny);
    if (comps.first.empty())
        throw InputError(label, "mask", "no cell to outline");

    MaskOutline out;
    std::vector<Ring> raw;
    const double cell_area = g.dx * g.dy;
    for (std::uint32_t id = 1; id <= comps.first.size(); ++id) {
        if (double(comps.cells[id - 1]) * cell_area < o.min_area) {
            ++out.dropped;
            continue;
        }
        Ring ring;
        for (const glm::ivec2 c : trace(comps, id, nx, ny))
            ring.push_back({std::clamp(g.x0 + (c.x - 0.5) * g.dx, g.x0, g.x_max()),
                            std::clamp(g.y0 + (c.y - 0.5) * g.dy, g.y0, g.y_max())});
        ring = tidy(ring);
        if (ring.size() >= 3)
            raw.push_back(std::move(ring));
    }
    // A component in another's hole is covered by that one's outer border.
    std::vector<Ring> outer;
    for (std::size_t a = 0; a < raw.size(); ++a) {
        bool nested = false;
        for (std::size_t b = 0; b < raw.size() && !nested; ++b)
            nested = b != a && inside_ring(raw[b], raw[a][0]);
        if (!nested)
            outer.push_back(raw[a]);
    }
    if (outer.empty())
        throw InputError(label, "mask", "every component is smaller than min_area");
    out.components = int(outer.size());

    double tol = o.tolerance > 0.0 ? o.tolerance : 0.5 * std::min(g.dx, g.dy);
    const double floor = 0.05 * std::min(g.dx, g.dy);
    for (;;) {
        Footprint f;
        for (const Ring& r : outer) {
            Ring s = tidy(simplify(r, tol));
            if (s.size() < 3)
                s = r;
            (f.polygon.empty() ? f.polygon : f.more.emplace_back()) = std::move(s);
        }
        bool ok = tol == 0.0;  // the raw outline is simple and exact by construction
        try {
            validate_footprint(f, label);
            ok = ok || respects(f, g, required, allowed);
        } catch (const InputError&) {
            if (tol == 0.0)
                throw;
            ok = false;
        }
        if (ok) {
            out.footprint = std::move(f);
            out.tolerance = tol;
            break;
        }
        tol = tol * 0.5 < floor ? 0.0 : tol * 0.5;
    }
    for (const Ring& r : footprint_polygons(out.footprint))
        out.vertices += r.size();
    return out;
}

}  // namespace kiri::geometry
