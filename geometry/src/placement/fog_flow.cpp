#include "kiri/geometry/fog_flow.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "kiri/geometry/error.hpp"

namespace kiri::geometry {
namespace {

// Bilinear sample of a cell-centred field at grid coordinates (fx, fy), clamped to the grid.
template <class T>
double bilinear(const std::vector<T>& a, int nx, int ny, double fx, double fy)
{
    fx = std::clamp(fx, 0.0, double(nx - 1));
    fy = std::clamp(fy, 0.0, double(ny - 1));
    const int i = std::min(int(fx), nx - 2), j = std::min(int(fy), ny - 2);
    const double s = fx - i, t = fy - j;
    const std::size_t k = std::size_t(j) * nx + i;
    return (1 - t) * ((1 - s) * double(a[k]) + s * double(a[k + 1])) + t * ((1 - s) * double(a[k + nx]) + s * double(a[k + nx + 1]));
}

void check(bool ok, const std::string& label, const char* key, const std::string& why)
{
    if (!ok)
        throw InputError(label, std::string("flow/") + key, why);
}

}  // namespace

void flow_step(const Heightfield& hf, std::vector<double>& h, const FlowOptions& o, double dt, FlowWork& w,
               double* outflow_m3, double* evaporated_m3, double* max_speed_ms)
{
    const int nx = hf.nx, ny = hf.ny;
    const std::size_t n = hf.size();
    w.u.resize(n);
    w.v.resize(n);
    w.next.assign(n, 0.0);
    const std::vector<double>& g = hf.z;
    const double wind_speed = glm::length(o.wind);
    const glm::dvec2 wind_dir = wind_speed > 0.0 ? o.wind / wind_speed : glm::dvec2(0.0);
    const double reach = std::max(hf.dx, hf.dy);  // "one cell downwind"
    double fastest = 0.0;

    // Velocities. The fog's surface is ground + thickness; where there is none, the ground.
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const std::size_t k = std::size_t(j) * nx + i;
            auto eta = [&](int a, int b) {
                const std::size_t q = std::size_t(b) * nx + a;
                return g[q] + h[q];
            };
            const int i0 = std::max(0, i - 1), i1 = std::min(nx - 1, i + 1);
            const int j0 = std::max(0, j - 1), j1 = std::min(ny - 1, j + 1);
            glm::dvec2 grad(i1 > i0 ? (eta(i1, j) - eta(i0, j)) / ((i1 - i0) * hf.dx) : 0.0,
                            j1 > j0 ? (eta(i, j1) - eta(i, j0)) / ((j1 - j0) * hf.dy) : 0.0);
            glm::dvec2 vel = -o.spread * grad;
            const double gl = glm::length(vel);
            if (gl > o.max_speed)
                vel *= o.max_speed / gl;
            if (h[k] > 0.0 && wind_speed > 0.0) {
                // Only the part of the column above the ground one cell downwind can go on.
                const double ahead = bilinear(g, nx, ny, i + wind_dir.x * reach / hf.dx, j + wind_dir.y * reach / hf.dy);
                const double free_share = std::clamp((g[k] + h[k] - ahead) / h[k], 0.0, 1.0);
                vel += o.coupling * free_share * o.wind;
            }
            w.u[k] = float(vel.x);
            w.v[k] = float(vel.y);
        }

    const double cell = hf.dx * hf.dy, step_cells = std::min(hf.dx, hf.dy);
    double out = 0.0, evaporated = 0.0;
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const std::size_t k = std::size_t(j) * nx + i;
            double m = h[k];
            if (m <= 0.0)
                continue;
            // Follow the column in grid coordinates, sub-steps of at most one cell (at most 64).
            double fx = i, fy = j;
            const double speed = std::hypot(double(w.u[k]), double(w.v[k]));
            fastest = std::max(fastest, speed);
            const int subs = std::clamp(int(std::ceil(speed * dt / step_cells)), 1, 64);
            const double sdt = dt / subs;
            double descent = 0.0, ground = g[k];
            for (int s = 0; s < subs; ++s) {
                const double du = bilinear(w.u, nx, ny, fx, fy), dv = bilinear(w.v, nx, ny, fx, fy);
                fx += du * sdt / hf.dx;
                fy += dv * sdt / hf.dy;
                const double here = bilinear(g, nx, ny, fx, fy);
                descent += std::max(0.0, ground - here);
                ground = here;
            }
            if (o.evaporation_depth > 0.0 && descent > 0.0) {
                const double kept = m * std::exp(-descent / o.evaporation_depth);
                evaporated += (m - kept) * cell;
                m = kept;
            }
            // Spread over the four cells around the landing point; weights outside the grid
            // leave it.
            const double ffx = std::floor(fx), ffy = std::floor(fy);
            const double s = fx - ffx, t = fy - ffy;
            const int a = int(ffx), b = int(ffy);
            const double wts[4] = {(1 - s) * (1 - t), s * (1 - t), (1 - s) * t, s * t};
            const int ci[4] = {a, a + 1, a, a + 1}, cj[4] = {b, b, b + 1, b + 1};
            for (int c = 0; c < 4; ++c) {
                if (wts[c] == 0.0)
                    continue;
                if (ci[c] < 0 || cj[c] < 0 || ci[c] >= nx || cj[c] >= ny)
                    out += wts[c] * m * cell;
                else
                    w.next[std::size_t(cj[c]) * nx + ci[c]] += wts[c] * m;
            }
        }
    h.swap(w.next);
    if (outflow_m3)
        *outflow_m3 += out;
    if (evaporated_m3)
        *evaporated_m3 += evaporated;
    if (max_speed_ms)
        *max_speed_ms = std::max(*max_speed_ms, fastest);
}

std::vector<double> flow_fog(const Heightfield& hf, std::vector<double> h, const FlowOptions& o, FlowReport* report,
                             const std::string& label)
{
    check(std::isfinite(o.wind.x) && std::isfinite(o.wind.y) && glm::length(o.wind) <= 100.0, label, "wind",
          "must be a finite wind of at most 100 m/s");
    check(o.duration >= 0.0 && o.duration <= 30 * 86400.0, label, "duration", "must be in [0, 2592000] seconds");
    check(o.time_step > 0.0 && o.time_step <= 86400.0, label, "time_step", "must be in (0, 86400] seconds");
    check(o.coupling >= 0.0 && o.coupling <= 1.0, label, "coupling", "must be in [0, 1]");
    check(o.spread >= 0.0 && std::isfinite(o.spread), label, "spread", "must be a finite number >= 0 (m/s)");
    check(o.max_speed > 0.0 && o.max_speed <= 100.0, label, "max_speed", "must be in (0, 100] m/s");
    check(o.evaporation_depth >= 0.0 && std::isfinite(o.evaporation_depth), label, "evaporation_depth",
          "must be a finite number >= 0 (metres; 0 = no evaporation)");
    check(o.duration / o.time_step <= 1e6, label, "time_step", "more than a million steps");
    if (h.size() != hf.size())
        throw InputError(label, "flow", "the thickness field is not on the terrain's grid");
    for (double v : h)
        if (!(v >= 0.0) || !std::isfinite(v))
            throw InputError(label, "flow", "thickness must be finite and >= 0");
    FlowReport rep;
    const double cell = hf.dx * hf.dy;
    std::vector<std::uint8_t> had(h.size());
    for (std::size_t k = 0; k < h.size(); ++k) {
        rep.volume_before_m3 += h[k] * cell;
        had[k] = h[k] > 0.0;
    }
    FlowWork work;
    for (double t = 0.0; t < o.duration - 1e-9; t += o.time_step, ++rep.steps)
        flow_step(hf, h, o, std::min(o.time_step, o.duration - t), work, &rep.outflow_m3, &rep.evaporated_m3,
                  &rep.max_speed_ms);
    for (std::size_t k = 0; k < h.size(); ++k) {
        rep.volume_after_m3 += h[k] * cell;
        rep.moved_out_m3 += had[k] ? 0.0 : h[k] * cell;
    }
    if (report)
        *report = rep;
    return h;
}

}  // namespace kiri::geometry
