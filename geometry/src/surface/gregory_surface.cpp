// The Gregory network behind the Surface interface.
#include <algorithm>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/surface/surface.hpp"
#include "surface/gregory_basis.hpp"
#include "surface/gregory_network.hpp"

namespace kiri::geometry {
namespace {

class GregorySurface final : public Surface {
public:
    explicit GregorySurface(const PolyMesh& mesh) : map_(build_gregory_network(mesh))
    {
        support_ = map_.support;
        points_.resize(mesh.n_vertices());
        for (auto v : mesh.vertices()) {
            const auto p = mesh.point(v);
            points_[v.idx()] = {p[0], p[1], p[2]};
        }
        control_points_changed();
    }
    SurfaceKind kind() const override { return SurfaceKind::gregory; }

    PatchPoint evaluate(int face, double u, double v) const override
    {
        check_face(face);
        return geometry::evaluate(patches_[face], u, v);
    }
    void evaluate_into(int face, std::span<const double> u, std::span<const double> v,
                       const PatchSampleSpans& out) const override
    {
        check_face(face);
        geometry::evaluate_into(patches_[face], u, v, out);
    }
    void weights(int face, double u, double v, std::span<double> w, std::span<double> wu,
                 std::span<double> wv) const override
    {
        check_face(face);
        const std::size_t n = support_[face].size();
        if (w.size() < n || wu.size() < n || wv.size() < n)
            throw InputError("", "weights", "spans shorter than the support");
        double g[20], gu[20], gv[20];
        gregory_weights(u, v, g, gu, gv);
        const auto& M = map_.matrix[face];
        std::fill_n(w.begin(), n, 0.0);
        std::fill_n(wu.begin(), n, 0.0);
        std::fill_n(wv.begin(), n, 0.0);
        for (int k = 0; k < 20; ++k)
            for (std::size_t s = 0; s < n; ++s) {
                const double m = M[k * n + s];
                w[s] += g[k] * m;
                wu[s] += gu[k] * m;
                wv[s] += gv[k] * m;
            }
    }
    const GregoryPatch* gregory_patch(int face) const override
    {
        check_face(face);
        return &patches_[face];
    }

private:
    void control_points_changed() override
    {
        patches_.resize(map_.num_faces());
        for (int f = 0; f < map_.num_faces(); ++f)
            patches_[f] = map_.patch(f, points_);
    }
    GregoryNetworkMap map_;
    std::vector<GregoryPatch> patches_;
};

}  // namespace

std::unique_ptr<Surface> make_gregory_surface(const PolyMesh& mesh) { return std::make_unique<GregorySurface>(mesh); }

}  // namespace kiri::geometry
