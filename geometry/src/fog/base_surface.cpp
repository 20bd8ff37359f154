#include "kiri/geometry/fog/base_surface.hpp"

#include <chrono>
#include <cmath>

#include "fog/fit_samples.hpp"
#include "fog/fit_solver.hpp"
#include "fog/fit_steps.hpp"
#include "kiri/geometry/core/error.hpp"
#include "surface/face_stencil.hpp"

namespace kiri::geometry {
namespace {

// Seconds between laps, for the report's timings.
class Stopwatch {
public:
    double lap()
    {
        const auto now = std::chrono::steady_clock::now();
        const double seconds = std::chrono::duration<double>(now - start_).count();
        start_ = now;
        return seconds;
    }

private:
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace

const char* to_string(FitMode mode) { return mode == FitMode::blanket ? "blanket" : "lake"; }

BaseSurface::BaseSurface(ControlMesh control, SurfaceKind kind) : control_(std::move(control)), kind_(kind)
{
    stencils_ = kind == SurfaceKind::gregory ? make_gregory_stencils(control_.mesh)
                                             : make_catmull_clark_stencils(control_.mesh);
    surface_ = make_surface(control_.mesh, kind);
}
BaseSurface::~BaseSurface() = default;
BaseSurface::BaseSurface(BaseSurface&&) noexcept = default;
BaseSurface& BaseSurface::operator=(BaseSurface&&) noexcept = default;

std::vector<double> BaseSurface::heights() const
{
    std::vector<double> z;
    z.reserve(control_.mesh.n_vertices());
    for (auto v : control_.mesh.vertices())
        z.push_back(control_.mesh.point(v)[2]);
    return z;
}

void BaseSurface::set_heights(const std::vector<double>& z)
{
    if (z.size() != control_.mesh.n_vertices())
        throw InputError("", "heights", "expected one height per control vertex");
    for (auto v : control_.mesh.vertices()) {
        auto p = control_.mesh.point(v);
        p[2] = z[v.idx()];
        control_.mesh.set_point(v, p);
    }
    std::vector<glm::dvec3> points(z.size());
    for (auto v : control_.mesh.vertices()) {
        const auto p = control_.mesh.point(v);
        points[v.idx()] = {p[0], p[1], p[2]};
    }
    surface_->set_control_points(points);
}

glm::dvec3 BaseSurface::evaluate(int face, double u, double v, glm::dvec3* du, glm::dvec3* dv) const
{
    const PatchPoint q = surface_->evaluate(face, u, v);
    if (du)
        *du = q.du;
    if (dv)
        *dv = q.dv;
    return q.position;
}

bool BaseSurface::place_samples(const Heightfield& hf, int per_side)
{
    const std::vector<double> key = {double(hf.nx), double(hf.ny), hf.dx, hf.dy, hf.x0, hf.y0, double(per_side)};
    if (samples_ && samples_key_ == key)
        return true;
    samples_ = std::make_shared<const FitSamples>(make_fit_samples(control_, *stencils_, hf, per_side, true));
    samples_key_ = key;
    return false;
}

FitReport BaseSurface::fit(const Terrain& terrain, const FitOptions& o)
{
    validate_fit_options(o);
    FitReport rep;
    Stopwatch clock;
    const FitTarget target = make_fit_target(terrain.heightfield(), o);
    rep.seconds_target = clock.lap();

    rep.samples_per_patch = o.samples_per_patch > 0 ? o.samples_per_patch : 4;
    rep.samples_reused = place_samples(terrain.heightfield(), rep.samples_per_patch);
    rep.grid_vertex_samples = samples_->grid_vertex_samples;
    const FitLayout layout = make_fit_layout(control_, *stencils_, *samples_);
    const FitAssembly assembly = assemble_fit(layout, terrain, target, o);
    rep.nodata_samples = assembly.samples.without_data;
    rep.samples = assembly.samples.with_data + assembly.samples.without_data;
    require_fog(assembly.samples, o);
    std::vector<double> pull_targets = vertex_targets(layout, target);
    rep.seconds_assemble = clock.lap();

    FitSolver solver(layout, std::move(pull_targets));
    std::vector<double> z = solver.solve(assembly.faces);
    if (o.mode == FitMode::blanket) {
        z = enforce_clearance(layout, assembly, o, solver, std::move(z), rep.active_constraints);
        rep.local_lift = lift_locally(layout, assembly, o.clearance, z);
    }
    const std::vector<double> at_samples = surface_at_samples(layout, assembly, z);
    if (o.mode == FitMode::blanket)
        rep.lift = lift_uniformly(worst_shortfall(assembly.samples, o.clearance, at_samples), z);
    measure_fit(assembly.samples, at_samples, rep);
    rep.iterations = solver.solves();
    for (double h : z)
        if (!std::isfinite(h))
            throw InputError("", "fit", "the fit produced a non-finite height");
    set_heights(z);
    rep.seconds_solve = clock.lap();
    return rep;
}

}  // namespace kiri::geometry
