#include <stdexcept>

#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include "surface/face_stencil.hpp"

namespace kiri::geometry {
namespace {
using namespace OpenSubdiv;

class CatmullClarkStencils final : public FaceStencils {
public:
    explicit CatmullClarkStencils(const PolyMesh& mesh)
    {
        std::vector<int> counts, indices;
        for (auto f : mesh.faces()) {
            int n = 0;
            for (auto v : mesh.fv_range(f)) {
                indices.push_back(v.idx());
                ++n;
            }
            counts.push_back(n);
        }
        Far::TopologyDescriptor desc;
        desc.numVertices = static_cast<int>(mesh.n_vertices());
        desc.numFaces = static_cast<int>(mesh.n_faces());
        desc.numVertsPerFace = counts.data();
        desc.vertIndicesPerFace = indices.data();
        Sdc::Options sdc;
        // The default (VTX_BOUNDARY_NONE) drops the boundary faces of an open mesh.
        sdc.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
        using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
        refiner_.reset(Factory::Create(desc, Factory::Options(Sdc::SCHEME_CATMARK, sdc)));
        if (!refiner_)
            throw std::runtime_error("OpenSubdiv refused the control mesh topology");
        Bfr::RefinerSurfaceFactory<> factory(*refiner_);
        surfaces_.resize(mesh.n_faces());
        support_.resize(mesh.n_faces());
        for (int f = 0; f < desc.numFaces; ++f) {
            if (!factory.InitVertexSurface<double>(f, &surfaces_[f]))
                throw std::runtime_error("OpenSubdiv has no limit surface for face " + std::to_string(f));
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
