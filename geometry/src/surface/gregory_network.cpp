#include "surface/gregory_network.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <utility>

#include "kiri/geometry/core/error.hpp"

namespace kiri::geometry {
namespace {

using HH = PolyMesh::HalfedgeHandle;
using VH = PolyMesh::VertexHandle;
using FH = PolyMesh::FaceHandle;
constexpr double kPi = std::numbers::pi;

// An affine (or, for tangents, zero-sum) combination of mesh vertices.
struct Comb {
    std::vector<std::pair<int, double>> t;
    Comb& add(int v, double w)
    {
        t.emplace_back(v, w);
        return *this;
    }
    Comb& add(const Comb& c, double s)
    {
        for (const auto& [v, w] : c.t)
            t.emplace_back(v, w * s);
        return *this;
    }
    void compact()
    {
        std::sort(t.begin(), t.end());
        std::vector<std::pair<int, double>> o;
        for (const auto& e : t)
            if (!o.empty() && o.back().first == e.first)
                o.back().second += e.second;
            else
                o.push_back(e);
        t = std::move(o);
    }
};

Comb vertex(int v)
{
    Comb c;
    return c.add(v, 1.0);
}

// One vertex's fan: outgoing halfedges h_0..h_{m-1} counter-clockwise, face(h_j) between
// h_j and h_{j+1}. Boundary: h_0 and h_{m-1} are the boundary edges, m - 1 faces.
struct Fan {
    std::vector<HH> h;
    bool boundary = false;
    int faces() const { return boundary ? int(h.size()) - 1 : int(h.size()); }
};

class Builder {
public:
    explicit Builder(const PolyMesh& m) : m_(m) {}

    GregoryNetworkMap run()
    {
        for (auto f : m_.faces())
            if (m_.valence(f) != 4)
                throw InputError(
                    "", "control mesh/face " + std::to_string(f.idx()),
                    "the Gregory network needs quads (this face has " + std::to_string(m_.valence(f)) + " vertices)");
        const int nv = int(m_.n_vertices());
        p_.resize(nv);
        c_.assign(nv, 0.0);
        ep_.resize(m_.n_halfedges());
        for (int v = 0; v < nv; ++v)
            vertex_rules(VH(v));
        GregoryNetworkMap out;
        out.support.resize(m_.n_faces());
        out.matrix.resize(m_.n_faces());
        for (auto f : m_.faces())
            face_rules(f, out.support[f.idx()], out.matrix[f.idx()]);
        return out;
    }

private:
    Fan fan(VH v) const
    {
        Fan fan;
        HH start;
        int boundary_starts = 0;
        for (auto h : m_.voh_range(v))
            if (!m_.is_boundary(h) && m_.is_boundary(m_.opposite_halfedge_handle(h))) {
                start = h;
                ++boundary_starts;
            }
        if (boundary_starts > 1)
            throw InputError("", "control mesh/vertex " + std::to_string(v.idx()),
                             "non-manifold vertex (several boundary fans)");
        fan.boundary = boundary_starts == 1;
        if (!fan.boundary) {
            start = m_.halfedge_handle(v);
            if (!start.is_valid())
                throw InputError("", "control mesh/vertex " + std::to_string(v.idx()), "isolated vertex");
        }
        HH h = start;
        do {
            fan.h.push_back(h);
            if (m_.is_boundary(h))
                break;
            h = m_.opposite_halfedge_handle(m_.prev_halfedge_handle(h));
        } while (h != start && fan.h.size() <= m_.n_halfedges());
        return fan;
    }

    int to(HH h) const { return m_.to_vertex_handle(h).idx(); }
    Comb mid(HH h) const
    {
        Comb c;
        return c.add(m_.from_vertex_handle(h).idx(), 0.5).add(to(h), 0.5);
    }
    Comb centroid(FH f) const
    {
        Comb c;
        for (auto v : m_.fv_range(f))
            c.add(v.idx(), 0.25);
        return c;
    }

    void vertex_rules(VH vh)
    {
        const int v = vh.idx();
        const Fan F = fan(vh);
        const int m = int(F.h.size());
        if (!F.boundary) {
            // LSNC interior: Catmull-Clark limit position and tangents ([Loop09]).
            const int n = m;
            Comb p;
            p.add(v, double(n) * n / (n * (n + 5.0)));
            for (int j = 0; j < n; ++j) {
                p.add(to(F.h[j]), 4.0 / (n * (n + 5.0)));
                p.add(to(m_.next_halfedge_handle(F.h[j])), 1.0 / (n * (n + 5.0)));
            }
            p.compact();
            p_[v] = p;
            const double cn = std::cos(kPi / n), c2n = std::cos(2 * kPi / n);
            const double sigma = 1.0 / std::sqrt(4.0 + cn * cn);
            const double lambda = (5.0 + c2n + cn * std::sqrt(18.0 + 2.0 * c2n)) / 16.0;
            c_[v] = c2n;
            for (int i = 0; i < n; ++i) {
                Comb q;
                for (int j = 0; j < n; ++j) {
                    const HH h = F.h[(i + j) % n];
                    q.add(mid(h), (2.0 / n) * (1.0 - sigma * cn) * std::cos(2 * kPi * j / n));
                    q.add(centroid(m_.face_handle(h)), (2.0 / n) * 2.0 * sigma * std::cos((2 * kPi * j + kPi) / n));
                }
                Comb e = p;
                e.add(q, 2.0 / 3.0 * lambda);
                e.compact();
                ep_[F.h[i].idx()] = e;
            }
            return;
        }
        const int k = m - 1;  // faces
        const int w0 = to(F.h[0]), wk = to(F.h[k]);
        if (k == 1) {
            // Corner (valence 2): interpolated, the two boundary curves meet at an angle;
            // tensor B-spline rules with the boundary rows extrapolated (OpenSubdiv's
            // EDGE_AND_CORNER corner patch).
            p_[v] = vertex(v);
            c_[v] = 0.0;
            for (int j : {0, 1}) {
                Comb e;
                ep_[F.h[j].idx()] = e.add(v, 2.0 / 3.0).add(to(F.h[j]), 1.0 / 3.0);
            }
            return;
        }
        // Smooth boundary vertex with k >= 2 faces: boundary curve = cubic B-spline of the
        // boundary vertices (the Catmull-Clark boundary limit); edge points on the half disc
        // p + cos(j pi/k) A + sin(j pi/k) B, so they share one tangent plane; B reproduces the
        // bicubic B-spline for k = 2.
        Comb p;
        p.add(w0, 1.0 / 6).add(v, 4.0 / 6).add(wk, 1.0 / 6);
        p_[v] = p;
        c_[v] = std::cos(kPi / k);
        Comb A;
        A.add(w0, 1.0 / 6).add(wk, -1.0 / 6);
        Comb B, Fm, Em;
        double sf = 0.0, se = 0.0;
        for (int f = 0; f < k; ++f)
            sf += std::sin((f + 0.5) * kPi / k);
        for (int j = 1; j < k; ++j)
            se += std::sin(j * kPi / k);
        for (int f = 0; f < k; ++f)
            Fm.add(centroid(m_.face_handle(F.h[f])), std::sin((f + 0.5) * kPi / k) / sf);
        for (int j = 1; j < k; ++j)
            Em.add(mid(F.h[j]), std::sin(j * kPi / k) / se);
        // B = 2/9 [2 (F - v) + (E - v) - (m_0 - v) - (m_k - v)]
        B.add(Fm, 4.0 / 9).add(Em, 2.0 / 9).add(mid(F.h[0]), -2.0 / 9).add(mid(F.h[k]), -2.0 / 9).add(v, -2.0 / 9);
        for (int j = 0; j <= k; ++j) {
            Comb e = p;
            if (j == 0)
                e.add(A, 1.0);
            else if (j == k)
                e.add(A, -1.0);
            else
                e.add(A, std::cos(j * kPi / k)).add(B, std::sin(j * kPi / k));
            e.compact();
            ep_[F.h[j].idx()] = e;
        }
    }

    // LSNC face point of corner v_a = from(h_out) on the edge of h_out (outgoing from v_a),
    // inside face `in`; m_in is the midpoint of in's other edge at v_a; `out` (maybe invalid)
    // the face across the edge with m_out its other edge's midpoint:
    //   f = (1/3) [c_far p + (3 - 2 c_near - c_far) e + 2 c_near e' + r],
    //   r = (1/3)(m_in - m_out) + (2/3)(c_in - c_out).
    // On a boundary edge the missing face is the reflection of `in` (m_out = 2 v - m_in,
    // c_out = 2 mid(edge) - c_in), which gives the B-spline's points on regular boundaries.
    Comb face_point(HH h_out, FH in, const Comb& m_in, FH out, const Comb& m_out_if_any) const
    {
        const int a = m_.from_vertex_handle(h_out).idx(), b = to(h_out);
        const Comb& e = ep_[h_out.idx()];
        const Comb& e2 = ep_[m_.opposite_halfedge_handle(h_out).idx()];
        const double cn = c_[a], cf = c_[b];
        const Comb cin = centroid(in);
        Comb r;
        r.add(m_in, 1.0 / 3).add(cin, 2.0 / 3);
        if (out.is_valid()) {
            r.add(m_out_if_any, -1.0 / 3).add(centroid(out), -2.0 / 3);
        } else {
            Comb mo, co;
            mo.add(a, 2.0).add(m_in, -1.0);
            co.add(mid(h_out), 2.0).add(cin, -1.0);
            r.add(mo, -1.0 / 3).add(co, -2.0 / 3);
        }
        Comb f;
        f.add(p_[a], cf / 3).add(e, (3.0 - 2.0 * cn - cf) / 3).add(e2, 2.0 * cn / 3).add(r, 1.0 / 3);
        return f;
    }

    void face_rules(FH f, std::vector<int>& support, std::vector<double>& matrix) const
    {
        HH hc[4];  // hc[a]: the face's halfedge from corner a to corner a+1 (fv order)
        {
            VH c[4];
            int a = 0;
            for (auto v : m_.fv_range(f))
                c[a++] = v;
            for (a = 0; a < 4; ++a)
                hc[a] = m_.find_halfedge(c[a], c[(a + 1) % 4]);
        }
        Comb P[20];
        auto idx = [](int i, int j, int k) { return GregoryPatch::index(i, j, k); };
        // Corner a at patch position (ci, cj), its edge to a+1 along direction (du, dv).
        const int ci[4] = {0, 3, 3, 0}, cj[4] = {0, 0, 3, 3};
        for (int a = 0; a < 4; ++a) {
            const HH fwd = hc[a];                             // a -> a+1
            const HH prv = hc[(a + 3) % 4];                   // a-1 -> a
            const HH bwd = m_.opposite_halfedge_handle(prv);  // a -> a-1
            const int v = m_.from_vertex_handle(fwd).idx();
            P[idx(ci[a], cj[a], 0)] = p_[v];
            // Unit steps along the patch towards a+1 and towards a-1.
            const int nxt = (a + 1) % 4, prev = (a + 3) % 4;
            const int si = (ci[nxt] - ci[a]) / 3, sj = (cj[nxt] - cj[a]) / 3;
            const int ti = (ci[prev] - ci[a]) / 3, tj = (cj[prev] - cj[a]) / 3;
            P[idx(ci[a] + si, cj[a] + sj, 0)] = ep_[fwd.idx()];
            P[idx(ci[a] + ti, cj[a] + tj, 0)] = ep_[bwd.idx()];
            // Face points: the interior position next to the corner; k = 0 belongs to the
            // edges v = 0, 1 (u-direction edges), k = 1 to the edges u = 0, 1.
            const int ii = ci[a] == 0 ? 1 : 2, jj = cj[a] == 0 ? 1 : 2;
            const FH out_f = m_.face_handle(m_.opposite_halfedge_handle(fwd));
            Comb mo_f;
            if (out_f.is_valid())
                mo_f = mid(m_.next_halfedge_handle(m_.opposite_halfedge_handle(fwd)));
            const Comb ff = face_point(fwd, f, mid(bwd), out_f, mo_f);
            const FH out_b = m_.face_handle(bwd);
            Comb mo_b;
            if (out_b.is_valid())
                mo_b = mid(m_.opposite_halfedge_handle(m_.prev_halfedge_handle(bwd)));
            const Comb fb = face_point(bwd, f, mid(fwd), out_b, mo_b);
            const bool fwd_is_u = sj == 0;
            P[idx(ii, jj, fwd_is_u ? 0 : 1)] = ff;
            P[idx(ii, jj, fwd_is_u ? 1 : 0)] = fb;
        }
        support.clear();
        for (auto& c : P) {
            c.compact();
            for (const auto& e : c.t)
                support.push_back(e.first);
        }
        std::sort(support.begin(), support.end());
        support.erase(std::unique(support.begin(), support.end()), support.end());
        const std::size_t n = support.size();
        matrix.assign(20 * n, 0.0);
        for (int k = 0; k < 20; ++k)
            for (const auto& [vtx, w] : P[k].t) {
                const auto s = std::lower_bound(support.begin(), support.end(), vtx) - support.begin();
                matrix[k * n + s] += w;
            }
    }

    const PolyMesh& m_;
    std::vector<Comb> p_;    // per vertex: limit position
    std::vector<double> c_;  // per vertex: cos of the angle between consecutive edges
    std::vector<Comb> ep_;   // per outgoing halfedge: the edge point at its from-vertex
};

}  // namespace

GregoryPatch GregoryNetworkMap::patch(int face, const std::vector<glm::dvec3>& X) const
{
    const auto& S = support[face];
    const auto& M = matrix[face];
    const std::size_t n = S.size();
    // Relative to the first support vertex: exact for far-away coordinates (rows sum to 1).
    const glm::dvec3 o = X[S[0]];
    GregoryPatch::Points P;
    for (int k = 0; k < 20; ++k) {
        glm::dvec3 s(0.0);
        for (std::size_t i = 0; i < n; ++i)
            s += M[k * n + i] * (X[S[i]] - o);
        P[k] = s + o;
    }
    return GregoryPatch(P);
}

GregoryNetworkMap build_gregory_network(const PolyMesh& mesh) { return Builder(mesh).run(); }

}  // namespace kiri::geometry
