#include <string>

#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>

#include "kiri/geometry/core/error.hpp"
#include "surface/face_stencil.hpp"
#include "surface/osd_refiner.hpp"

namespace kiri::geometry {
namespace {
using namespace OpenSubdiv;

class CatmullClarkStencils final : public FaceStencils {
public:
    explicit CatmullClarkStencils(const PolyMesh& mesh)
    {
        refiner_ = make_catmark_refiner(mesh);  // one topology rule for both users
        Bfr::RefinerSurfaceFactory<> factory(*refiner_);
        surfaces_.resize(mesh.n_faces());
        support_.resize(mesh.n_faces());
        for (int f = 0; f < int(mesh.n_faces()); ++f) {
            if (!factory.InitVertexSurface<double>(f, &surfaces_[f]))
                throw InputError("", "control mesh/face " + std::to_string(f), "OpenSubdiv has no limit surface");
            support_[f].resize(surfaces_[f].GetNumControlPoints());
            surfaces_[f].GetControlPointIndices(support_[f].data());
        }
    }

    bool regular(int face) const override { return surfaces_[face].IsRegular(); }

    void weights(int face, double u, double v, FaceWeights& out, int order) const override
    {
        const auto& s = surfaces_[face];
        const std::size_t n = support_[face].size();
        out.w.resize(n);
        out.wu.resize(n);
        out.wv.resize(n);
        const double uv[2] = {u, v};
        if (order == 0) {
            s.EvaluateStencil(uv, out.w.data());
        } else if (order >= 2) {
            out.wuu.resize(n);
            out.wuv.resize(n);
            out.wvv.resize(n);
            s.EvaluateStencil(uv, out.w.data(), out.wu.data(), out.wv.data(), out.wuu.data(), out.wuv.data(),
                              out.wvv.data());
        } else {
            s.EvaluateStencil(uv, out.w.data(), out.wu.data(), out.wv.data());
        }
    }

private:
    std::unique_ptr<Far::TopologyRefiner> refiner_;
    std::vector<Bfr::Surface<double>> surfaces_;
};
}  // namespace

std::unique_ptr<FaceStencils> make_catmull_clark_stencils(const PolyMesh& mesh)
{
    return std::make_unique<CatmullClarkStencils>(mesh);
}

}  // namespace kiri::geometry
