// The fit's view of the Gregory network: weights of the mesh vertices = the 20 Gregory
// weights (gregory_basis, the one source, with exact second derivatives) times the LSNC map
// of the face (gregory_network.cpp; boundary rules in kiri/geometry/surface/surface.hpp).
#include <cstdint>

#include "surface/face_stencil.hpp"
#include "surface/gregory_basis.hpp"
#include "surface/gregory_network.hpp"

namespace kiri::geometry {
namespace {

class GregoryStencils final : public FaceStencils {
public:
    explicit GregoryStencils(const PolyMesh& mesh) : map_(build_gregory_network(mesh))
    {
        support_ = map_.support;
        // The tensor B-spline (affine in (u, v) over a square grid) unless a corner is an
        // irregular interior vertex or a boundary vertex with 3 or more faces.
        regular_.assign(mesh.n_faces(), 1);
        for (auto f : mesh.faces())
            for (auto v : mesh.fv_range(f))
                if (mesh.is_boundary(v) ? mesh.valence(v) > 3 : mesh.valence(v) != 4)
                    regular_[f.idx()] = 0;
    }

    bool regular(int face) const override { return regular_[face]; }

    void weights(int face, double u, double v, FaceWeights& out, int order) const override
    {
        double g[6][20];
        if (order >= 2)
            detail::gregory_basis<2>(u, v, 1, g[0], g[1], g[2], g[3], g[4], g[5]);
        else if (order == 1)
            detail::gregory_basis<1>(u, v, 1, g[0], g[1], g[2]);
        else
            detail::gregory_basis<0>(u, v, 1, g[0]);
        const int count = order >= 2 ? 6 : order == 1 ? 3 : 1;
        std::vector<double>* dst[6] = {&out.w, &out.wu, &out.wv, &out.wuu, &out.wuv, &out.wvv};
        const auto& M = map_.matrix[face];
        const std::size_t n = support_[face].size();
        for (int o = 0; o < count; ++o) {
            std::vector<double>& d = *dst[o];
            d.assign(n, 0.0);
            for (int k = 0; k < 20; ++k)
                if (g[o][k] != 0.0)
                    for (std::size_t s = 0; s < n; ++s)
                        d[s] += g[o][k] * M[k * n + s];
        }
    }

private:
    GregoryNetworkMap map_;
    std::vector<std::uint8_t> regular_;
};

}  // namespace

std::unique_ptr<FaceStencils> make_gregory_stencils(const PolyMesh& mesh)
{
    return std::make_unique<GregoryStencils>(mesh);
}

}  // namespace kiri::geometry
