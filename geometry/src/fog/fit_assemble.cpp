// The fit's steps up to the normal equations: options, target, layout, assembly.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "fog/fit_steps.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/fog/fog_target.hpp"

namespace kiri::geometry {
namespace {

std::string six_digits(double v)
{
    std::ostringstream s;
    s << v;
    return s.str();
}

void require_finite(double v, const char* field)
{
    if (!std::isfinite(v))
        throw InputError("", field, "must be a finite number");
}

// Samples of face f: the terrain and target under each, and the data rows of those with data.
void add_data_term(const FitLayout& layout, int f, const Terrain& terrain, const FitTarget& target, const FitOptions& o,
                   FitAssembly& out)
{
    const Heightfield& hf = terrain.heightfield();
    const FitSamples& smp = layout.samples;
    const auto& S = layout.stencils.support(f);
    const std::size_t n = S.size();
    SampleHeights& heights = out.samples;
    FaceWeights fw;
    for (std::size_t id = smp.face_begin[f]; id < smp.face_begin[f + 1]; ++id) {
        layout.stencils.weights(f, smp.uv[id].x, smp.uv[id].y, fw, 0);
        std::copy(fw.w.begin(), fw.w.end(),
                  out.weights.begin() + std::ptrdiff_t(out.face_weights[f] + (id - smp.face_begin[f]) * n));
        glm::dvec2 xy(0.0);
        for (std::size_t k = 0; k < n; ++k)
            xy += fw.w[k] * layout.relative_xy[S[k]];
        xy += layout.origin;
        heights.terrain[id] = terrain.height(xy.x, xy.y);
        heights.target[id] = target.at(xy.x, xy.y);
        if (!has_data(hf, xy.x, xy.y)) {
            ++heights.without_data;
            continue;
        }
        heights.has_data[id] = 1;
        ++heights.with_data;
        // Blanket: fit the upper envelope of the target and terrain + clearance, so the
        // constraint iterations start close to feasible.
        const double fit_to = o.mode == FitMode::blanket
            ? std::max(heights.target[id], heights.terrain[id] + o.clearance)
            : heights.target[id];
        add_row(out.faces[f], fw.w, out.data_weight[f], fit_to);
    }
}

// The thin-plate energy of face f, smoothness h^4 (z_xx^2 + 2 z_xy^2 + z_yy^2) by 3 x 3 Gauss
// quadrature over the face's xy area.
void add_thin_plate_term(const FitLayout& layout, int f, double smoothness, FaceSystem& system)
{
    const double gq[3] = {0.5 - 0.5 * std::sqrt(0.6), 0.5, 0.5 + 0.5 * std::sqrt(0.6)};
    const double gw[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
    const double h = layout.patch_size;
    const auto& S = layout.stencils.support(f);
    const std::size_t n = S.size();
    const std::vector<glm::dvec2>& rel = layout.relative_xy;
    FaceWeights fw;
    std::vector<double> hxx, hxy, hyy;
    for (int qb = 0; qb < 3; ++qb)
        for (int qa = 0; qa < 3; ++qa) {
            layout.stencils.weights(f, gq[qa], gq[qb], fw, 2);
            glm::dvec2 au(0.0), av(0.0), auu(0.0), auv(0.0), avv(0.0);
            for (std::size_t k = 0; k < n; ++k) {
                au += fw.wu[k] * rel[S[k]];
                av += fw.wv[k] * rel[S[k]];
                auu += fw.wuu[k] * rel[S[k]];
                auv += fw.wuv[k] * rel[S[k]];
                avv += fw.wvv[k] * rel[S[k]];
            }
            const double det = au.x * av.y - av.x * au.y;
            if (!(std::abs(det) > 1e-12 * h * h))
                continue;
            // z_x, z_y from z_u, z_v; then the xy Hessian H = J^-T A J^-1 with
            // A = [z_uu - grad z . x_uu, ...] (chain rule; x(u, v) is fixed, so H is linear in z).
            const double M[2][2] = {{av.y / det, -av.x / det}, {-au.y / det, au.x / det}};
            hxx.assign(n, 0.0);
            hxy.assign(n, 0.0);
            hyy.assign(n, 0.0);
            for (std::size_t k = 0; k < n; ++k) {
                const double gx = (av.y * fw.wu[k] - au.y * fw.wv[k]) / det;
                const double gy = (-av.x * fw.wu[k] + au.x * fw.wv[k]) / det;
                const double A[2][2] = {{fw.wuu[k] - gx * auu.x - gy * auu.y, fw.wuv[k] - gx * auv.x - gy * auv.y},
                                        {fw.wuv[k] - gx * auv.x - gy * auv.y, fw.wvv[k] - gx * avv.x - gy * avv.y}};
                auto H = [&](int i, int j) {
                    double s = 0.0;
                    for (int c = 0; c < 2; ++c)
                        for (int d = 0; d < 2; ++d)
                            s += M[c][i] * A[c][d] * M[d][j];
                    return s;
                };
                hxx[k] = H(0, 0);
                hxy[k] = H(0, 1);
                hyy[k] = H(1, 1);
            }
            const double beta = smoothness * h * h * h * h * gw[qa] * gw[qb] * std::abs(det) / (h * h);
            add_row(system, hxx, beta, 0.0);
            add_row(system, hxy, 2.0 * beta, 0.0);
            add_row(system, hyy, beta, 0.0);
        }
}

}  // namespace

void validate_fit_options(const FitOptions& o)
{
    for (auto [v, name] : {std::pair{o.offset, "offset"},
                           {o.smoothing_length, "smoothing"},
                           {o.altitude, "altitude"},
                           {o.clearance, "clearance"},
                           {o.thickness, "thickness"},
                           {o.smoothness, "smoothness"}})
        require_finite(v, name);
    if (o.smoothness < 0.0)
        throw InputError("", "smoothness", "must be >= 0");
    if (o.mode == FitMode::blanket) {
        if (o.clearance < 0.0)
            throw InputError("", "clearance", "must be >= 0");
        if (!(o.thickness > 0.0))
            throw InputError("", "thickness", "must be > 0");
        if (o.clearance > o.thickness)
            throw InputError("", "clearance",
                             "clearance " + six_digits(o.clearance) + " m is larger than the fog thickness " +
                                 six_digits(o.thickness) + " m: the fog would never touch the ground");
    }
}

double FitTarget::at(double x, double y) const
{
    if (mode == FitMode::blanket)
        return sample_bilinear(smooth, x, y) + offset;
    return altitude_grid ? sample_bilinear(*altitude_grid, x, y) : altitude;
}

FitTarget make_fit_target(const Heightfield& terrain, const FitOptions& o)
{
    FitTarget t;
    t.mode = o.mode;
    t.smooth = o.mode == FitMode::blanket ? smooth_heightfield(terrain, o.smoothing_length) : Heightfield{};
    t.offset = o.offset;
    t.altitude = o.altitude;
    t.altitude_grid = o.altitude_grid;
    return t;
}

FitLayout make_fit_layout(const ControlMesh& control, const FaceStencils& stencils, const FitSamples& samples)
{
    FitLayout layout{stencils, samples, control.origin, std::vector<glm::dvec2>(control.num_vertices()),
                     control.patch_size};
    for (int v = 0; v < control.num_vertices(); ++v) {
        const auto p = control.mesh.point(PolyMesh::VertexHandle(v));
        layout.relative_xy[v] = glm::dvec2(p[0], p[1]) - control.origin;
    }
    return layout;
}

void add_row(FaceSystem& s, const double* w, std::size_t n, double weight, double rhs)
{
    for (std::size_t a = 0; a < n; ++a) {
        const double wa = weight * w[a];
        s.r[a] += wa * rhs;
        for (std::size_t b = 0; b < n; ++b)
            s.L[a * n + b] += wa * w[b];
    }
}

FitAssembly assemble_fit(const FitLayout& layout, const Terrain& terrain, const FitTarget& target, const FitOptions& o)
{
    const int nf = layout.num_faces();
    const FitSamples& smp = layout.samples;
    const std::size_t ns = smp.uv.size();
    FitAssembly out;
    out.data_weight.resize(nf);
    for (int f = 0; f < nf; ++f)
        out.data_weight[f] = 1.0 / double(std::max<std::size_t>(1, smp.face_begin[f + 1] - smp.face_begin[f]));
    out.samples.terrain.resize(ns);
    out.samples.target.resize(ns);
    out.samples.has_data.assign(ns, 0);
    out.faces.resize(nf);
    out.face_weights.resize(nf);
    std::size_t weights = 0;
    for (int f = 0; f < nf; ++f) {
        out.face_weights[f] = weights;
        weights += (smp.face_begin[f + 1] - smp.face_begin[f]) * layout.stencils.support(f).size();
    }
    out.weights.resize(weights);
    for (int f = 0; f < nf; ++f) {
        const std::size_t n = layout.stencils.support(f).size();
        out.faces[f].L.assign(n * n, 0.0);
        out.faces[f].r.assign(n, 0.0);
        add_data_term(layout, f, terrain, target, o, out);
        if (o.smoothness > 0.0)
            add_thin_plate_term(layout, f, o.smoothness, out.faces[f]);
    }
    return out;
}

void require_fog(const SampleHeights& samples, const FitOptions& o)
{
    if (samples.with_data == 0)
        throw InputError("", "footprint", "no terrain data under the footprint (all samples are nodata)");
    if (o.mode != FitMode::lake)
        return;
    long long below = 0;
    for (std::size_t id = 0; id < samples.has_data.size(); ++id)
        below += samples.has_data[id] && samples.terrain[id] < samples.target[id];
    if (below == 0)
        throw InputError(
            "", "altitude",
            (o.altitude_grid ? std::string("the fog top") : "the lake altitude " + six_digits(o.altitude) + " m") +
                " is below the terrain everywhere in the footprint: no fog");
}

std::vector<double> vertex_targets(const FitLayout& layout, const FitTarget& target)
{
    std::vector<double> z(layout.num_vertices());
    for (int v = 0; v < layout.num_vertices(); ++v)
        z[v] = target.at(layout.relative_xy[v].x + layout.origin.x, layout.relative_xy[v].y + layout.origin.y);
    return z;
}

}  // namespace kiri::geometry
