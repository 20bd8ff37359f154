#include "surface/osd_refiner.hpp"

#include <vector>

#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include "kiri/geometry/core/error.hpp"

namespace kiri::geometry {

std::unique_ptr<OpenSubdiv::Far::TopologyRefiner> make_catmark_refiner(const PolyMesh& mesh)
{
    using namespace OpenSubdiv;
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
    sdc.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    std::unique_ptr<Far::TopologyRefiner> r(Factory::Create(desc, Factory::Options(Sdc::SCHEME_CATMARK, sdc)));
    if (!r)
        throw InputError("", "control mesh", "OpenSubdiv refused the topology");
    return r;
}

}  // namespace kiri::geometry
