// The Catmull-Clark limit surface (OpenSubdiv Bfr) behind the Surface interface.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/surface/surface.hpp"
#include "surface/osd_refiner.hpp"

namespace kiri::geometry {
namespace {
using namespace OpenSubdiv;

// A face parameter: NaN -> centre, else clamped to [0,1].
double clamp_face_parameter(double t)
{
    const double c = std::clamp(t, 0.0, 1.0);
    return c == c ? c : 0.5;
}

class LimitSurface final : public Surface {
public:
    explicit LimitSurface(const PolyMesh& mesh) : refiner_(make_catmark_refiner(mesh))
    {
        // One factory, used here only (its cache is not thread-safe); the Bfr::Surface objects
        // it fills are read-only afterwards.
        Bfr::RefinerSurfaceFactory<> factory(*refiner_);
        const int nf = int(mesh.n_faces());
        surfaces_.resize(nf);
        support_.resize(nf);
        for (int f = 0; f < nf; ++f) {
            if (!factory.InitVertexSurface<double>(f, &surfaces_[f]))
                throw InputError("", "control mesh/face " + std::to_string(f), "OpenSubdiv has no limit surface");
            support_[f].resize(surfaces_[f].GetNumControlPoints());
            surfaces_[f].GetControlPointIndices(support_[f].data());
        }
        points_.resize(mesh.n_vertices());
        for (auto v : mesh.vertices()) {
            const auto p = mesh.point(v);
            points_[v.idx()] = {p[0], p[1], p[2]};
        }
        control_points_changed();
    }
    SurfaceKind kind() const override { return SurfaceKind::catmull_clark; }

    PatchPoint evaluate(int face, double u, double v) const override
    {
        check_face(face);
        PatchPoint r;
        eval(face, clamp_face_parameter(u), clamp_face_parameter(v), r.position, r.du, r.dv);
        r.normal = normal(face, u, v, r.du, r.dv);
        return r;
    }

    void evaluate_into(int face, std::span<const double> u, std::span<const double> v,
                       const PatchSampleSpans& out) const override
    {
        check_face(face);
        const std::size_t n = u.size();
        if (v.size() != n)
            throw InputError("", "v", "u and v must have the same size");
        for (auto s : {out.px, out.py, out.pz, out.dux, out.duy, out.duz, out.dvx, out.dvy, out.dvz})
            if (s.size() < n)
                throw InputError("", "out", "an output span is shorter than the batch");
        const bool normals = !out.nx.empty();
        if (normals && (out.nx.size() < n || out.ny.size() < n || out.nz.size() < n))
            throw InputError("", "out.normal", "a normal span is shorter than the batch");
        for (std::size_t i = 0; i < n; ++i) {
            glm::dvec3 p, du, dv;
            eval(face, clamp_face_parameter(u[i]), clamp_face_parameter(v[i]), p, du, dv);
            out.px[i] = p.x, out.py[i] = p.y, out.pz[i] = p.z;
            out.dux[i] = du.x, out.duy[i] = du.y, out.duz[i] = du.z;
            out.dvx[i] = dv.x, out.dvy[i] = dv.y, out.dvz[i] = dv.z;
            if (normals) {
                const glm::dvec3 nn = normal(face, u[i], v[i], du, dv);
                out.nx[i] = nn.x, out.ny[i] = nn.y, out.nz[i] = nn.z;
            }
        }
    }

    void weights(int face, double u, double v, std::span<double> w, std::span<double> wu,
                 std::span<double> wv) const override
    {
        check_face(face);
        const std::size_t n = support_[face].size();
        if (w.size() < n || wu.size() < n || wv.size() < n)
            throw InputError("", "weights", "spans shorter than the support");
        const double uv[2] = {clamp_face_parameter(u), clamp_face_parameter(v)};
        surfaces_[face].EvaluateStencil(uv, w.data(), wu.data(), wv.data());
    }

private:
    void eval(int face, double u, double v, glm::dvec3& p, glm::dvec3& du, glm::dvec3& dv) const
    {
        const double uv[2] = {u, v};
        double P[3], Du[3], Dv[3];
        const double* pp = patch_points_.data() + 3 * std::size_t(offset_[face]);
        surfaces_[face].Evaluate(uv, pp, Bfr::Surface<double>::PointDescriptor(3), P, Du, Dv);
        p = glm::dvec3(P[0], P[1], P[2]) + origin_;
        du = {Du[0], Du[1], Du[2]};
        dv = {Dv[0], Dv[1], Dv[2]};
    }

    glm::dvec3 normal(int face, double u, double v, const glm::dvec3& du, const glm::dvec3& dv) const
    {
        auto ok = [](const glm::dvec3& n, const glm::dvec3& a, const glm::dvec3& b) {
            const double l = glm::length(n);
            return std::isfinite(l) && l > 0.0 && l > 1e-14 * glm::length(a) * glm::length(b);
        };
        glm::dvec3 n = glm::cross(du, dv);
        if (ok(n, du, dv))
            return glm::normalize(n);
        u = clamp_face_parameter(u);
        v = clamp_face_parameter(v);
        glm::dvec3 p, a, b;
        eval(face, u + (u < 0.5 ? 1e-7 : -1e-7), v + (v < 0.5 ? 1e-7 : -1e-7), p, a, b);
        n = glm::cross(a, b);
        return ok(n, a, b) ? glm::normalize(n) : glm::dvec3(0.0, 0.0, 1.0);
    }

    void control_points_changed() override
    {
        // Relative to one origin: keeps 1e7 m offsets out of Bfr's sums.
        origin_ = points_.empty() ? glm::dvec3(0.0) : points_[0];
        std::vector<double> rel(3 * points_.size());
        for (std::size_t i = 0; i < points_.size(); ++i)
            for (int c = 0; c < 3; ++c)
                rel[3 * i + c] = points_[i][c] - origin_[c];
        offset_.resize(surfaces_.size() + 1);
        offset_[0] = 0;
        for (std::size_t f = 0; f < surfaces_.size(); ++f)
            offset_[f + 1] = offset_[f] + surfaces_[f].GetNumPatchPoints();
        patch_points_.assign(3 * std::size_t(offset_.back()), 0.0);
        for (std::size_t f = 0; f < surfaces_.size(); ++f)
            surfaces_[f].PreparePatchPoints(rel.data(), Bfr::Surface<double>::PointDescriptor(3),
                                            patch_points_.data() + 3 * std::size_t(offset_[f]),
                                            Bfr::Surface<double>::PointDescriptor(3));
    }

    std::unique_ptr<Far::TopologyRefiner> refiner_;
    std::vector<Bfr::Surface<double>> surfaces_;
    std::vector<int> offset_;
    std::vector<double> patch_points_;
    glm::dvec3 origin_{0.0};
};

}  // namespace

std::unique_ptr<Surface> make_limit_surface(const PolyMesh& mesh) { return std::make_unique<LimitSurface>(mesh); }

}  // namespace kiri::geometry
