// Gregory patch network over a quad mesh as fixed linear combinations of the mesh vertices:
// per face, the 20 control points of a bicubic Gregory patch (REFERENCE 1.1), built with the
// rules of Loop, Schaefer, Ni and Castano 2009 (REFERENCE 5) at interior vertices of any
// valence. Boundary vertices (not covered by LSNC) use the local bicubic B-spline rules of a
// boundary with linearly extrapolated phantom points (the rules Catmull-Clark's limit obeys
// there): on a regular boundary the patch is exactly the Catmull-Clark limit patch; at a
// concave boundary corner it is an approximation without a G1 guarantee.
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "surface/face_stencil.hpp"

namespace kiri::geometry {
namespace {

// A point as a linear combination of mesh vertices.
using Lin = std::map<int, double>;

Lin vtx(int v) { return {{v, 1.0}}; }
Lin operator+(Lin a, const Lin& b)
{
    for (const auto& [k, w] : b)
        a[k] += w;
    return a;
}
Lin operator*(double s, Lin a)
{
    for (auto& [k, w] : a)
        w *= s;
    return a;
}
Lin operator-(const Lin& a, const Lin& b) { return a + (-1.0) * b; }

using HE = PolyMesh::HalfedgeHandle;

struct Builder {
    const PolyMesh& m;

    int from(HE h) const { return m.from_vertex_handle(h).idx(); }
    int to(HE h) const { return m.to_vertex_handle(h).idx(); }
    // Next outgoing halfedge counter-clockwise around from(h) (faces are counter-clockwise).
    HE ccw(HE h) const { return m.opposite_halfedge_handle(m.prev_halfedge_handle(h)); }
    Lin centroid(PolyMesh::FaceHandle f) const
    {
        Lin c;
        int n = 0;
        for (auto v : m.fv_range(f)) {
            c[v.idx()] += 1.0;
            ++n;
        }
        return (1.0 / n) * c;
    }
    bool boundary_vertex(int v) const { return m.is_boundary(PolyMesh::VertexHandle(v)); }
    int valence(int v) const { return int(m.valence(PolyMesh::VertexHandle(v))); }

    // Outgoing halfedges of an interior vertex, counter-clockwise, starting at h.
    std::vector<HE> ring(HE h) const
    {
        std::vector<HE> r;
        HE c = h;
        do {
            r.push_back(c);
            c = ccw(c);
        } while (c != h && r.size() < 64);
        return r;
    }

    Lin corner_point(int v) const
    {
        const auto vh = PolyMesh::VertexHandle(v);
        if (boundary_vertex(v)) {
            std::vector<int> nb;
            for (auto h : m.voh_range(vh))
                if (m.is_boundary(m.edge_handle(h)))
                    nb.push_back(to(h));
            if (m.valence(vh) == 2 || nb.size() != 2)
                return vtx(v);  // corner: interpolated
            return (1.0 / 6.0) * (vtx(nb[0]) + 4.0 * vtx(v) + vtx(nb[1]));
        }
        const auto r = ring(m.halfedge_handle(vh));
        const double n = double(r.size());
        Lin p = (n * n) * vtx(v);
        for (HE h : r) {
            p = p + 4.0 * vtx(to(h));
            p = p + vtx(to(m.next_halfedge_handle(h)));  // diagonal vertex of the quad
        }
        return (1.0 / (n * (n + 5.0))) * p;
    }

    // Edge point of from(h) on the edge h (the Bezier point next to the corner).
    Lin edge_point(HE h, const Lin& p) const
    {
        const int v = from(h), w = to(h);
        if (m.is_boundary(m.edge_handle(h)))
            return (1.0 / 3.0) * (2.0 * vtx(v) + vtx(w));
        if (boundary_vertex(v)) {
            // Difference of the (1,4,1)/6 averages across the edge's two faces (phantom rule).
            const HE o = m.opposite_halfedge_handle(h);
            const int x = to(m.next_halfedge_handle(h)), xp = from(m.prev_halfedge_handle(h));
            const int y = from(m.prev_halfedge_handle(o)), yp = to(m.next_halfedge_handle(o));
            const Lin wa = (1.0 / 6.0) * (vtx(x) + 4.0 * vtx(w) + vtx(y));
            const Lin va = (1.0 / 6.0) * (vtx(xp) + 4.0 * vtx(v) + vtx(yp));
            return p + (1.0 / 3.0) * (wa - va);
        }
        const auto r = ring(h);
        const int n = int(r.size());
        const double pi = M_PI, sigma = 1.0 / std::sqrt(4.0 + std::pow(std::cos(pi / n), 2));
        const double lambda =
            (5.0 + std::cos(2.0 * pi / n) + std::cos(pi / n) * std::sqrt(18.0 + 2.0 * std::cos(2.0 * pi / n))) / 16.0;
        Lin q;
        for (int j = 0; j < n; ++j) {
            const Lin mid = 0.5 * (vtx(v) + vtx(to(r[j])));
            const Lin cen = centroid(m.face_handle(r[j]));
            q = q + ((1.0 - sigma * std::cos(pi / n)) * std::cos(2.0 * pi * j / n)) * mid +
                (2.0 * sigma * std::cos((2.0 * pi * j + pi) / n)) * cen;
        }
        return p + ((2.0 / 3.0) * lambda * (2.0 / n)) * q;
    }

    // Face point of corner from(h_out) in the face of h_out, tied to the edge `along` (h_out
    // itself or the face's other edge at the corner, `other`).
    Lin face_point(HE along, HE other, const Lin& p, const Lin& e_along, const Lin& e_other, bool along_is_out) const
    {
        const int v = from(along);
        const auto F = along_is_out ? m.face_handle(along) : m.opposite_face_handle(along);
        if (boundary_vertex(v)) {
            int d = -1;  // diagonal of v in F
            for (auto fv : m.fv_range(F))
                if (fv.idx() != v && fv.idx() != to(along) && fv.idx() != to(other))
                    d = fv.idx();
            return (1.0 / 9.0) * (4.0 * vtx(v) + 2.0 * vtx(to(along)) + 2.0 * vtx(to(other)) + vtx(d));
        }
        const double pi = M_PI;
        const double c_near = std::cos(2.0 * pi / valence(v));
        const int w = to(along);
        const double c_far = boundary_vertex(w) ? 0.0 : std::cos(2.0 * pi / valence(w));
        // The face across `along`, and v's other edge in it.
        const auto G = along_is_out ? m.opposite_face_handle(along) : m.face_handle(along);
        int out_nb = -1;
        for (auto h : m.fh_range(G))
            if (from(h) == v && to(h) != w)
                out_nb = to(h);
            else if (to(h) == v && from(h) != w)
                out_nb = from(h);
        const Lin m_in = 0.5 * (vtx(v) + vtx(to(other))), m_out = 0.5 * (vtx(v) + vtx(out_nb));
        const Lin r = (1.0 / 3.0) * (m_in - m_out) + (2.0 / 3.0) * (centroid(F) - centroid(G));
        const double d = 3.0;
        return (1.0 / d) * (c_far * p + (d - 2.0 * c_near - c_far) * e_along + (2.0 * c_near) * e_other + r);
    }
};

// Slot of boundary Bezier point b_ij (i along u, j along v) and of the interior pairs.
constexpr int slot(int i, int j) { return j * 4 + i; }
// k = 1 points of the interior positions (1,1), (2,1), (1,2), (2,2).
constexpr int slot1(int i, int j) { return 16 + (j - 1) * 2 + (i - 1); }

void bernstein(double t, double b[4], double d[4])
{
    const double s = 1.0 - t;
    b[0] = s * s * s;
    b[1] = 3.0 * t * s * s;
    b[2] = 3.0 * t * t * s;
    b[3] = t * t * t;
    d[0] = -3.0 * s * s;
    d[1] = 3.0 * s * s - 6.0 * t * s;
    d[2] = 6.0 * t * s - 3.0 * t * t;
    d[3] = 3.0 * t * t;
}

// The 20 weights of the Gregory patch at (u, v) and their first derivatives (REFERENCE 1.1).
// At the corner where a pair's blend is 0/0 its Bernstein weight is 0: take the mean.
void gregory_basis(double u, double v, double w[20], double wu[20], double wv[20])
{
    double bu[4], du[4], bv[4], dv[4];
    bernstein(u, bu, du);
    bernstein(v, bv, dv);
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            w[slot(i, j)] = bu[i] * bv[j];
            wu[slot(i, j)] = du[i] * bv[j];
            wv[slot(i, j)] = bu[i] * dv[j];
        }
    // Q = (a P0 + b P1) / (a + b), a and b affine in u or v: (a_u, a_v, b_u, b_v) below.
    struct Pair {
        int i, j;
        double a, b, au, av, bu, bv;
    };
    const Pair pairs[4] = {{1, 1, u, v, 1, 0, 0, 1},
                           {2, 1, 1 - u, v, -1, 0, 0, 1},
                           {1, 2, u, 1 - v, 1, 0, 0, -1},
                           {2, 2, 1 - u, 1 - v, -1, 0, 0, -1}};
    for (const Pair& p : pairs) {
        const int s0 = slot(p.i, p.j), s1 = slot1(p.i, p.j);
        const double B = w[s0], Bu = wu[s0], Bv = wv[s0], sum = p.a + p.b;
        if (sum <= 0.0) {
            w[s0] = w[s1] = 0.5 * B;
            wu[s0] = wu[s1] = 0.5 * Bu;
            wv[s0] = wv[s1] = 0.5 * Bv;
            continue;
        }
        const double f = p.a / sum;  // weight of P0
        const double fu = (p.au * p.b - p.a * p.bu) / (sum * sum), fv = (p.av * p.b - p.a * p.bv) / (sum * sum);
        w[s0] = B * f;
        w[s1] = B * (1.0 - f);
        wu[s0] = Bu * f + B * fu;
        wu[s1] = Bu * (1.0 - f) - B * fu;
        wv[s0] = Bv * f + B * fv;
        wv[s1] = Bv * (1.0 - f) - B * fv;
    }
}

class GregoryStencils final : public FaceStencils {
public:
    explicit GregoryStencils(const PolyMesh& m)
    {
        const Builder b{m};
        const int nf = int(m.n_faces());
        support_.resize(nf);
        matrix_.resize(nf);
        regular_.assign(nf, 1);
        for (auto f : m.faces())
            for (auto v : m.fv_range(f))
                if (!m.is_boundary(v) && m.valence(v) != 4)
                    regular_[f.idx()] = 0;
        std::vector<Lin> corner(m.n_vertices());
        std::vector<std::uint8_t> has_corner(m.n_vertices(), 0);
        for (auto f : m.faces()) {
            // Corner halfedges: h[k] runs from corner k to corner k+1 (fv order).
            std::vector<int> cv;
            for (auto v : m.fv_range(f))
                cv.push_back(v.idx());
            if (cv.size() != 4)
                throw std::runtime_error("the Gregory network needs a quad mesh");
            HE h[4];
            for (int k = 0; k < 4; ++k)
                h[k] = m.find_halfedge(PolyMesh::VertexHandle(cv[k]), PolyMesh::VertexHandle(cv[(k + 1) % 4]));
            Lin P[20];
            Lin p[4], ep[4], em[4], fp[4], fm[4];
            for (int k = 0; k < 4; ++k) {
                if (!has_corner[cv[k]]) {
                    corner[cv[k]] = b.corner_point(cv[k]);
                    has_corner[cv[k]] = 1;
                }
                p[k] = corner[cv[k]];
                const HE out = h[k];                                       // corner k -> k+1
                const HE back = m.opposite_halfedge_handle(h[(k + 3) % 4]);  // corner k -> k-1
                ep[k] = b.edge_point(out, p[k]);
                em[k] = b.edge_point(back, p[k]);
                fp[k] = b.face_point(out, back, p[k], ep[k], em[k], true);
                fm[k] = b.face_point(back, out, p[k], em[k], ep[k], false);
            }
            P[slot(0, 0)] = p[0];
            P[slot(3, 0)] = p[1];
            P[slot(3, 3)] = p[2];
            P[slot(0, 3)] = p[3];
            P[slot(1, 0)] = ep[0];
            P[slot(0, 1)] = em[0];
            P[slot(2, 0)] = em[1];
            P[slot(3, 1)] = ep[1];
            P[slot(3, 2)] = em[2];
            P[slot(2, 3)] = ep[2];
            P[slot(1, 3)] = em[3];
            P[slot(0, 2)] = ep[3];
            P[slot(1, 1)] = fp[0];
            P[slot1(1, 1)] = fm[0];
            P[slot(2, 1)] = fm[1];
            P[slot1(2, 1)] = fp[1];
            P[slot(2, 2)] = fp[2];
            P[slot1(2, 2)] = fm[2];
            P[slot(1, 2)] = fm[3];
            P[slot1(1, 2)] = fp[3];
            std::map<int, int> col;
            for (const Lin& l : P)
                for (const auto& [v, w] : l)
                    col.emplace(v, 0);
            auto& S = support_[f.idx()];
            for (auto& [v, c] : col) {
                c = int(S.size());
                S.push_back(v);
            }
            auto& M = matrix_[f.idx()];
            M.assign(20 * S.size(), 0.0);
            for (int s = 0; s < 20; ++s)
                for (const auto& [v, w] : P[s])
                    M[s * S.size() + col[v]] += w;
        }
    }

    bool regular(int face) const override { return regular_[face]; }

    void weights(int face, double u, double v, FaceWeights& out, int order) const override
    {
        double g[20], gu[20], gv[20];
        gregory_basis(u, v, g, gu, gv);
        apply(face, g, out.w);
        if (order == 0)
            return;
        apply(face, gu, out.wu);
        apply(face, gv, out.wv);
        if (order < 2)
            return;
        // Second derivatives by central differences of the exact first derivatives; used only
        // at interior quadrature points (the fit's thin-plate term).
        const double h = 1e-5;
        const double uc = std::clamp(u, h, 1.0 - h), vc = std::clamp(v, h, 1.0 - h);
        double a[20], au[20], av[20], c[20], cu[20], cv[20];
        gregory_basis(uc + h, vc, a, au, av);
        gregory_basis(uc - h, vc, c, cu, cv);
        double duu[20], duv[20], dvv[20];
        for (int k = 0; k < 20; ++k) {
            duu[k] = (au[k] - cu[k]) / (2 * h);
            duv[k] = (av[k] - cv[k]) / (2 * h);
        }
        gregory_basis(uc, vc + h, a, au, av);
        gregory_basis(uc, vc - h, c, cu, cv);
        for (int k = 0; k < 20; ++k) {
            dvv[k] = (av[k] - cv[k]) / (2 * h);
            duv[k] = 0.5 * (duv[k] + (au[k] - cu[k]) / (2 * h));
        }
        apply(face, duu, out.wuu);
        apply(face, duv, out.wuv);
        apply(face, dvv, out.wvv);
    }

private:
    void apply(int face, const double g[20], std::vector<double>& out) const
    {
        const std::size_t n = support_[face].size();
        const auto& M = matrix_[face];
        out.assign(n, 0.0);
        for (int s = 0; s < 20; ++s)
            if (g[s] != 0.0)
                for (std::size_t k = 0; k < n; ++k)
                    out[k] += g[s] * M[s * n + k];
    }

    std::vector<std::vector<double>> matrix_;  // per face: 20 x support
    std::vector<std::uint8_t> regular_;
};

}  // namespace

std::unique_ptr<FaceStencils> make_gregory_stencils(const PolyMesh& mesh)
{
    return std::make_unique<GregoryStencils>(mesh);
}

}  // namespace kiri::geometry
