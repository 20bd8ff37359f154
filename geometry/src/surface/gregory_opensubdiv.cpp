#include "kiri/geometry/surface/gregory_opensubdiv.hpp"

#include <opensubdiv/far/patchDescriptor.h>
#include <opensubdiv/far/patchParam.h>

#include "kiri/geometry/core/error.hpp"

// Exported by libosdCPU (explicit instantiation) but declared in far/patchBasis.h, which
// Debian does not install: the basis behind PatchTable::EvaluateBasis.
namespace OpenSubdiv {
namespace OPENSUBDIV_VERSION {
namespace Far {
namespace internal {
template <typename REAL>
int EvaluatePatchBasis(int patchType, PatchParam const& param, REAL s, REAL t, REAL wP[], REAL wDs[], REAL wDt[],
                       REAL wDss[], REAL wDst[], REAL wDtt[]);
}  // namespace internal
}  // namespace Far
}  // namespace OPENSUBDIV_VERSION
}  // namespace OpenSubdiv

namespace kiri::geometry {
namespace {
using OpenSubdiv::Far::PatchDescriptor;
using OpenSubdiv::Far::PatchParam;

// OpenSubdiv GREGORY_BASIS index of each storage index ([OpenSubdiv]: 5 points per corner,
// corners counter-clockwise from (0,0)).
constexpr int kFromOsd[20] = {
    // P_ij0, j*4 + i
    0, 1, 7, 5,      // j = 0: b00 b10 b20 b30
    2, 3, 9, 6,      // j = 1: b01 P110 P210 b31
    16, 19, 13, 12,  // j = 2: b02 P120 P220 b32
    15, 17, 11, 10,  // j = 3: b03 b13 b23 b33
    // P111, P211, P121, P221
    4, 8, 18, 14};

PatchParam base_param()
{
    PatchParam p;
    p.Clear();
    return p;
}
}  // namespace

void opensubdiv_gregory_weights(double u, double v, std::span<double, 20> w, std::span<double, 20> wu,
                                std::span<double, 20> wv)
{
    static const PatchParam param = base_param();
    double a[20], b[20], c[20];
    OpenSubdiv::Far::internal::EvaluatePatchBasis<double>(PatchDescriptor::GREGORY_BASIS, param, u, v, a, b, c, nullptr,
                                                          nullptr, nullptr);
    for (int k = 0; k < 20; ++k) {
        w[k] = a[kFromOsd[k]];
        wu[k] = b[kFromOsd[k]];
        wv[k] = c[kFromOsd[k]];
    }
}

void evaluate_into_opensubdiv(const GregoryPatch& patch, std::span<const double> u, std::span<const double> v,
                              const PatchSampleSpans& out)
{
    const std::size_t n = u.size();
    if (v.size() != n)
        throw InputError("", "v", "u and v must have the same size");
    for (auto s : {out.px, out.py, out.pz, out.dux, out.duy, out.duz, out.dvx, out.dvy, out.dvz})
        if (s.size() < n)
            throw InputError("", "out", "an output span is shorter than the batch");
    const PatchParam param = base_param();
    const auto& P = patch.points();
    glm::dvec3 q[20];  // in OpenSubdiv's order, as a patch table's control vertices would be
    for (int k = 0; k < 20; ++k)
        q[kFromOsd[k]] = P[k];
    for (std::size_t i = 0; i < n; ++i) {
        double a[20], b[20], c[20];
        OpenSubdiv::Far::internal::EvaluatePatchBasis<double>(PatchDescriptor::GREGORY_BASIS, param, u[i], v[i], a, b,
                                                              c, nullptr, nullptr, nullptr);
        glm::dvec3 p(0.0), du(0.0), dv(0.0);
        for (int k = 0; k < 20; ++k) {
            p += a[k] * q[k];
            du += b[k] * q[k];
            dv += c[k] * q[k];
        }
        out.px[i] = p.x, out.py[i] = p.y, out.pz[i] = p.z;
        out.dux[i] = du.x, out.duy[i] = du.y, out.duz[i] = du.z;
        out.dvx[i] = dv.x, out.dvy[i] = dv.y, out.dvz[i] = dv.z;
    }
}

}  // namespace kiri::geometry
