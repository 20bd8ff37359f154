#include "kiri/geometry/fog/tessellate.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "kiri/geometry/core/error.hpp"
#include "core/parallel_rows.hpp"

namespace kiri::geometry {
namespace {

struct Sample {
    glm::dvec3 p, n;
};

// (u, v) of the point at distance t along side s (corner s -> corner s+1) and d inwards.
// Each map is a rotation of the square, so counter-clockwise stays counter-clockwise.
glm::dvec2 side_param(int s, double t, double d)
{
    switch (s) {
    case 0: return {t, d};
    case 1: return {1.0 - d, t};
    case 2: return {1.0 - t, 1.0 - d};
    default: return {d, 1.0 - t};
    }
}

Sample eval(const BaseSurface& surface, int f, glm::dvec2 uv)
{
    const PatchPoint q = surface.surface().evaluate(f, uv.x, uv.y);
    return {q.position, q.normal};
}

// Topology of one patch: its corner vertices and, per side, the edge and its direction.
struct PatchSides {
    int corner[4];
    int edge[4];
    bool forward[4];  // side runs along the edge's halfedge 0
};

std::vector<PatchSides> patch_sides(const PolyMesh& m)
{
    std::vector<PatchSides> out(m.n_faces());
    for (auto f : m.faces()) {
        PatchSides& ps = out[f.idx()];
        int k = 0;
        for (auto v : m.fv_range(f))
            ps.corner[k++] = v.idx();
        for (int s = 0; s < 4; ++s) {
            const auto he =
                m.find_halfedge(PolyMesh::VertexHandle(ps.corner[s]), PolyMesh::VertexHandle(ps.corner[(s + 1) % 4]));
            const auto e = m.edge_handle(he);
            ps.edge[s] = e.idx();
            ps.forward[s] = he == m.halfedge_handle(e, 0);
        }
    }
    return out;
}

struct Built {
    TriMesh mesh;
    std::vector<double> face_error;  // filled when measured
};

double triangle_error(const BaseSurface& surface, int f, const glm::dvec2 uv[3], const glm::dvec3 p[3])
{
    static const double bary[10][3] = {{1 / 3.0, 1 / 3.0, 1 / 3.0},
                                       {0.5, 0.5, 0},
                                       {0, 0.5, 0.5},
                                       {0.5, 0, 0.5},
                                       {4 / 6.0, 1 / 6.0, 1 / 6.0},
                                       {1 / 6.0, 4 / 6.0, 1 / 6.0},
                                       {1 / 6.0, 1 / 6.0, 4 / 6.0},
                                       {0.25, 0.75, 0},
                                       {0, 0.25, 0.75},
                                       {0.75, 0, 0.25}};
    double e = 0.0;
    for (const auto& b : bary) {
        const glm::dvec2 q = b[0] * uv[0] + b[1] * uv[1] + b[2] * uv[2];
        const glm::dvec3 lin = b[0] * p[0] + b[1] * p[1] + b[2] * p[2];
        e = std::max(e, glm::length(surface.evaluate(f, q.x, q.y) - lin));
    }
    return e;
}

Built build(const BaseSurface& surface, const std::vector<PatchSides>& sides, const std::vector<int>& level,
            bool measure)
{
    const PolyMesh& cm = surface.control().mesh;
    const int nf = surface.num_patches();
    // One level per edge: the larger of its patches'.
    std::vector<int> edge_level(cm.n_edges(), 1);
    for (int f = 0; f < nf; ++f)
        for (int s = 0; s < 4; ++s)
            edge_level[sides[f].edge[s]] = std::max(edge_level[sides[f].edge[s]], level[f]);
    // Shared points, each evaluated once by its owner (the incident patch of smallest id).
    std::vector<Sample> corner(cm.n_vertices());
    std::vector<std::uint8_t> corner_done(cm.n_vertices(), 0);
    std::vector<std::vector<Sample>> edge_pts(cm.n_edges());
    for (int f = 0; f < nf; ++f)  // ascending f: the first patch to reach a point owns it
        for (int s = 0; s < 4; ++s) {
            const int v = sides[f].corner[s];
            if (!corner_done[v]) {
                corner[v] = eval(surface, f, side_param(s, 0.0, 0.0));
                corner_done[v] = 1;
            }
        }
    for (int f = 0; f < nf; ++f)
        for (int s = 0; s < 4; ++s) {
            const int e = sides[f].edge[s], L = edge_level[e];
            if (!edge_pts[e].empty())
                continue;
            edge_pts[e].resize(L + 1);
            for (int k = 1; k < L; ++k) {
                const int ke = sides[f].forward[s] ? k : L - k;
                edge_pts[e][ke] = eval(surface, f, side_param(s, double(k) / L, 0.0));
            }
        }

    Built out;
    TriMesh& mesh = out.mesh;
    mesh.request_vertex_normals();
    mesh.request_vertex_texcoords2D();
    OpenMesh::VPropHandleT<int> pid;
    mesh.add_property(pid, patch_id_property);
    mesh.property(pid).set_persistent(true);  // written by PLY with Options::Custom
    if (measure)
        out.face_error.assign(nf, 0.0);
    auto add = [&](const Sample& s, glm::dvec2 uv, int f) {
        const auto vh = mesh.add_vertex(TriMesh::Point(s.p.x, s.p.y, s.p.z));
        mesh.set_normal(vh, TriMesh::Normal(s.n.x, s.n.y, s.n.z));
        mesh.set_texcoord2D(vh, TriMesh::TexCoord2D(uv.x, uv.y));
        mesh.property(pid, vh) = f;
        return vh;
    };
    for (int f = 0; f < nf; ++f) {
        const PatchSides& ps = sides[f];
        int L[4];
        bool all_one = level[f] == 1;
        for (int s = 0; s < 4; ++s) {
            L[s] = edge_level[ps.edge[s]];
            all_one = all_one && L[s] == 1;
        }
        // Boundary ring of this patch: per side, L+1 handles (corners shared between sides).
        TriMesh::VertexHandle cvh[4];
        for (int s = 0; s < 4; ++s)
            cvh[s] = add(corner[ps.corner[s]], side_param(s, 0.0, 0.0), f);
        std::vector<TriMesh::VertexHandle> ring[4];
        for (int s = 0; s < 4; ++s) {
            ring[s].push_back(cvh[s]);
            for (int k = 1; k < L[s]; ++k) {
                const int ke = ps.forward[s] ? k : L[s] - k;
                ring[s].push_back(add(edge_pts[ps.edge[s]][ke], side_param(s, double(k) / L[s], 0.0), f));
            }
            ring[s].push_back(cvh[(s + 1) % 4]);
        }
        std::vector<std::array<TriMesh::VertexHandle, 3>> tris;
        if (all_one) {
            tris.push_back({cvh[0], cvh[1], cvh[2]});
            tris.push_back({cvh[0], cvh[2], cvh[3]});
        } else {
            const int N = std::max(level[f], 2);
            std::vector<TriMesh::VertexHandle> inner(std::size_t(N + 1) * (N + 1));
            auto in = [&](int a, int b) -> TriMesh::VertexHandle& { return inner[std::size_t(b) * (N + 1) + a]; };
            for (int b = 1; b < N; ++b)
                for (int a = 1; a < N; ++a) {
                    const glm::dvec2 uv(double(a) / N, double(b) / N);
                    in(a, b) = add(eval(surface, f, uv), uv, f);
                }
            for (int b = 1; b < N - 1; ++b)
                for (int a = 1; a < N - 1; ++a) {
                    tris.push_back({in(a, b), in(a + 1, b), in(a + 1, b + 1)});
                    tris.push_back({in(a, b), in(a + 1, b + 1), in(a, b + 1)});
                }
            // Transition strips: zip the side's L+1 points with the inner ring's N-1 points.
            for (int s = 0; s < 4; ++s) {
                std::vector<TriMesh::VertexHandle> inner_side;
                std::vector<double> inner_t;
                for (int m = 1; m < N; ++m) {
                    const glm::dvec2 uv = side_param(s, double(m) / N, 1.0 / N);
                    inner_side.push_back(in(int(std::lround(uv.x * N)), int(std::lround(uv.y * N))));
                    inner_t.push_back(double(m) / N);
                }
                const int M = int(inner_side.size()) - 1;
                int k = 0, m = 0;
                while (k < L[s] || m < M) {
                    const bool outer = m == M || (k < L[s] && double(k + 1) / L[s] <= inner_t[m + 1]);
                    if (outer) {
                        tris.push_back({ring[s][k], ring[s][k + 1], inner_side[m]});
                        ++k;
                    } else {
                        tris.push_back({ring[s][k], inner_side[m + 1], inner_side[m]});
                        ++m;
                    }
                }
            }
        }
        for (const auto& t : tris) {
            mesh.add_face(t[0], t[1], t[2]);
            if (measure) {
                glm::dvec2 uv[3];
                glm::dvec3 p[3];
                for (int c = 0; c < 3; ++c) {
                    const auto tc = mesh.texcoord2D(t[c]);
                    const auto q = mesh.point(t[c]);
                    uv[c] = {tc[0], tc[1]};
                    p[c] = {q[0], q[1], q[2]};
                }
                out.face_error[f] = std::max(out.face_error[f], triangle_error(surface, f, uv, p));
            }
        }
    }
    return out;
}

}  // namespace

Tessellation tessellate(const BaseSurface& surface, const TessellationOptions& o)
{
    if (o.level < 1)
        throw InputError("", "tessellation/level", "must be >= 1");
    if (!std::isfinite(o.tolerance) || o.tolerance < 0.0)
        throw InputError("", "tessellation/tolerance", "must be a finite number >= 0");
    if (o.max_level < 1)
        throw InputError("", "tessellation/max_level", "must be >= 1");
    const auto sides = patch_sides(surface.control().mesh);
    const int nf = surface.num_patches();
    Tessellation out;
    if (o.tolerance <= 0.0) {
        out.patch_level.assign(nf, o.level);
        out.mesh = build(surface, sides, out.patch_level, false).mesh;
        out.max_error = tessellation_error(surface, out.mesh);
        return out;
    }
    // Adaptive: start from the error of one bilinear cell (it falls as 1/N^2), then refine
    // the patches whose measured error is still above the tolerance.
    out.patch_level.assign(nf, 1);
    for (int f = 0; f < nf; ++f) {
        glm::dvec3 c[4];
        for (int s = 0; s < 4; ++s)
            c[s] = surface.evaluate(f, side_param(s, 0, 0).x, side_param(s, 0, 0).y);
        double e1 = 0.0;
        for (double v : {0.25, 0.5, 0.75})
            for (double u : {0.25, 0.5, 0.75}) {
                const glm::dvec3 bil = (1 - v) * ((1 - u) * c[0] + u * c[1]) + v * ((1 - u) * c[3] + u * c[2]);
                e1 = std::max(e1, glm::length(surface.evaluate(f, u, v) - bil));
            }
        out.patch_level[f] = std::clamp(int(std::ceil(std::sqrt(e1 / o.tolerance))), 1, o.max_level);
    }
    for (int round = 0; round < 16; ++round) {
        Built b = build(surface, sides, out.patch_level, true);
        bool refined = false;
        for (int f = 0; f < nf; ++f)
            if (b.face_error[f] > o.tolerance && out.patch_level[f] < o.max_level) {
                const double ratio = std::sqrt(b.face_error[f] / o.tolerance);
                out.patch_level[f] =
                    std::min(o.max_level, std::max(out.patch_level[f] + 1, int(std::ceil(out.patch_level[f] * ratio))));
                refined = true;
            }
        if (!refined) {
            out.max_error = *std::max_element(b.face_error.begin(), b.face_error.end());
            out.mesh = std::move(b.mesh);
            return out;
        }
    }
    out.mesh = build(surface, sides, out.patch_level, false).mesh;
    out.max_error = tessellation_error(surface, out.mesh);
    return out;
}

double tessellation_error(const BaseSurface& surface, const TriMesh& mesh)
{
    OpenMesh::VPropHandleT<int> pid;
    if (!mesh.get_property_handle(pid, patch_id_property) || !mesh.has_vertex_texcoords2D())
        throw InputError("", "mesh", "not a tessellation of a base surface (no patch ids or uv)");
    // Ten points of the surface a triangle: on every core, in blocks of faces (the largest is
    // the same in any order).
    const int faces = int(mesh.n_faces()), block = 1024, blocks = (faces + block - 1) / block;
    std::vector<double> largest(std::size_t(std::max(blocks, 0)), 0.0);
    detail::for_rows_in_parallel(0, blocks, [&](auto next_block) {
        for (int k = next_block(); k < blocks; k = next_block())
            for (int i = k * block; i < std::min(faces, (k + 1) * block); ++i) {
                glm::dvec2 uv[3];
                glm::dvec3 p[3];
                int c = 0, patch = -1;
                for (auto v : mesh.fv_range(mesh.face_handle(i))) {
                    const auto tc = mesh.texcoord2D(v);
                    const auto q = mesh.point(v);
                    uv[c] = {tc[0], tc[1]};
                    p[c] = {q[0], q[1], q[2]};
                    patch = mesh.property(pid, v);
                    ++c;
                }
                largest[std::size_t(k)] = std::max(largest[std::size_t(k)], triangle_error(surface, patch, uv, p));
            }
    });
    double e = 0.0;
    for (const double b : largest)
        e = std::max(e, b);
    return e;
}

}  // namespace kiri::geometry
