#include "fog/fit_samples.hpp"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace kiri::geometry {
namespace {

struct FaceFrame {
    glm::ivec2 cell{0};                    // grid cell of the face (min corner index)
    glm::dvec2 c0{0.0}, e1{0.0}, e2{0.0};  // cell coordinates of corner 0 and the u, v axes
    bool affine = false;
};

}  // namespace

FitSamples make_fit_samples(const ControlMesh& cm, const FaceStencils& st, const Heightfield& hf, int per_side,
                            bool grid_vertices)
{
    const PolyMesh& m = cm.mesh;
    const int nf = cm.num_faces(), nv = cm.num_vertices();
    const double h = cm.patch_size;
    std::vector<glm::dvec2> rel(nv);
    std::vector<std::uint8_t> at_rest(nv);
    for (int v = 0; v < nv; ++v) {
        const auto p = m.point(PolyMesh::VertexHandle(v));
        rel[v] = glm::dvec2(p[0], p[1]) - cm.origin;
        const glm::dvec2 rest = cm.grid_origin + h * glm::dvec2(cm.grid[v]) - cm.origin;
        at_rest[v] = glm::dvec2(std::abs(rest.x - rel[v].x), std::abs(rest.y - rel[v].y)) == glm::dvec2(0.0) ||
            (std::abs(rest.x - rel[v].x) < 1e-9 * h && std::abs(rest.y - rel[v].y) < 1e-9 * h);
    }
    // Faces by grid cell, and each face's (u, v) <-> cell-coordinate frame.
    glm::ivec2 lo(1 << 30), hi(-(1 << 30));
    for (const auto& g : cm.grid) {
        lo = glm::min(lo, g);
        hi = glm::max(hi, g);
    }
    const int cw = std::max(1, hi.x - lo.x), ch = std::max(1, hi.y - lo.y);
    std::vector<int> cell_face(std::size_t(cw) * ch, -1);
    std::vector<FaceFrame> frame(nf);
    for (auto f : m.faces()) {
        glm::ivec2 g[4];
        int k = 0;
        for (auto v : m.fv_range(f))
            g[k++] = cm.grid[v.idx()];
        FaceFrame& fr = frame[f.idx()];
        fr.cell = glm::min(glm::min(g[0], g[1]), glm::min(g[2], g[3]));
        fr.c0 = glm::dvec2(g[0] - fr.cell);
        fr.e1 = glm::dvec2(g[1] - g[0]);
        fr.e2 = glm::dvec2(g[3] - g[0]);
        fr.affine = st.regular(f.idx());
        for (int v : st.support(f.idx()))
            fr.affine = fr.affine && at_rest[v];
        cell_face[std::size_t(fr.cell.y - lo.y) * cw + (fr.cell.x - lo.x)] = f.idx();
    }
    auto face_at = [&](int ci, int cj) {
        if (ci < lo.x || cj < lo.y || ci >= lo.x + cw || cj >= lo.y + ch)
            return -1;
        return cell_face[std::size_t(cj - lo.y) * cw + (ci - lo.x)];
    };
    FaceWeights fw;
    auto xy_of = [&](int f, double u, double v, glm::dvec2* du, glm::dvec2* dv) {
        st.weights(f, u, v, fw, du ? 1 : 0);
        const auto& S = st.support(f);
        glm::dvec2 p(0.0), pu(0.0), pv(0.0);
        for (std::size_t k = 0; k < S.size(); ++k) {
            p += fw.w[k] * rel[S[k]];
            if (du) {
                pu += fw.wu[k] * rel[S[k]];
                pv += fw.wv[k] * rel[S[k]];
            }
        }
        if (du) {
            *du = pu;
            *dv = pv;
        }
        return p;
    };
    // (u, v) of local point q (relative to origin) in face f, if it lies in the face.
    auto locate = [&](int f, glm::dvec2 q, glm::dvec2& uv) {
        const FaceFrame& fr = frame[f];
        const glm::dvec2 s = (q + cm.origin - cm.grid_origin) / h - glm::dvec2(fr.cell) - fr.c0;
        const double det = fr.e1.x * fr.e2.y - fr.e1.y * fr.e2.x;
        uv = {(s.x * fr.e2.y - s.y * fr.e2.x) / det, (fr.e1.x * s.y - fr.e1.y * s.x) / det};
        const double eps = 1e-12;
        if (fr.affine)
            return uv.x >= -eps && uv.x <= 1 + eps && uv.y >= -eps && uv.y <= 1 + eps;
        uv = glm::clamp(uv, 0.0, 1.0);
        for (int it = 0; it < 12; ++it) {
            glm::dvec2 du, dv;
            const glm::dvec2 r = q - xy_of(f, uv.x, uv.y, &du, &dv);
            const double d = du.x * dv.y - du.y * dv.x;
            if (!(std::abs(d) > 0.0))
                return false;
            const glm::dvec2 step((r.x * dv.y - r.y * dv.x) / d, (du.x * r.y - du.y * r.x) / d);
            uv = glm::clamp(uv + step, -0.25, 1.25);
            if (glm::length(r) < 1e-9 * h && std::abs(step.x) + std::abs(step.y) < 1e-9)
                break;
        }
        if (!(glm::length(q - xy_of(f, uv.x, uv.y, nullptr, nullptr)) < 1e-6 * h))
            return false;
        if (uv.x < -1e-9 || uv.x > 1 + 1e-9 || uv.y < -1e-9 || uv.y > 1 + 1e-9)
            return false;
        uv = glm::clamp(uv, 0.0, 1.0);
        return true;
    };

    std::vector<std::vector<glm::dvec2>> per_face(nf);
    for (int f = 0; f < nf; ++f)
        for (int b = 0; b < per_side; ++b)
            for (int a = 0; a < per_side; ++a)
                per_face[f].emplace_back((a + 0.5) / per_side, (b + 0.5) / per_side);
    FitSamples out;
    if (grid_vertices) {
        // Terrain vertices in the mesh's bounding box; each is looked up in its grid cell's
        // face, then in the 8 neighbours (snapping moves faces across cell lines).
        glm::dvec2 bmin(1e300), bmax(-1e300);
        for (const auto& r : rel) {
            bmin = glm::min(bmin, r);
            bmax = glm::max(bmax, r);
        }
        const int i0 = std::max(0, int(std::ceil((bmin.x + cm.origin.x - hf.x0) / hf.dx)));
        const int i1 = std::min(hf.nx - 1, int(std::floor((bmax.x + cm.origin.x - hf.x0) / hf.dx)));
        const int j0 = std::max(0, int(std::ceil((bmin.y + cm.origin.y - hf.y0) / hf.dy)));
        const int j1 = std::min(hf.ny - 1, int(std::floor((bmax.y + cm.origin.y - hf.y0) / hf.dy)));
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) {
                // Relative coordinates computed from the grid directly keep 1e7 m offsets exact.
                const glm::dvec2 q((hf.x0 - cm.origin.x) + i * hf.dx, (hf.y0 - cm.origin.y) + j * hf.dy);
                const glm::dvec2 s = (q + cm.origin - cm.grid_origin) / h;
                const int ci = int(std::floor(s.x)), cj = int(std::floor(s.y));
                glm::dvec2 uv;
                bool found = false, near_mesh = false;
                for (int k = 0; k < 9 && !found; ++k) {
                    const int f = face_at(ci + (k == 0 ? 0 : (k - 1) % 3 - 1), cj + (k == 0 ? 0 : (k - 1) / 3 - 1));
                    if (f < 0 || (k > 0 && frame[f].affine))
                        continue;
                    near_mesh = near_mesh || !frame[f].affine || k == 0;
                    if (locate(f, q, uv)) {
                        per_face[f].push_back(uv);
                        found = true;
                    }
                }
                out.grid_vertex_samples += found;
                out.unresolved += !found && near_mesh && face_at(ci, cj) >= 0 && !frame[face_at(ci, cj)].affine;
            }
    }
    out.face_begin.assign(nf + 1, 0);
    for (int f = 0; f < nf; ++f)
        out.face_begin[f + 1] = out.face_begin[f] + per_face[f].size();
    out.uv.reserve(out.face_begin[nf]);
    for (int f = 0; f < nf; ++f)
        for (const auto& uv : per_face[f])
            out.uv.push_back(uv);
    return out;
}

}  // namespace kiri::geometry
