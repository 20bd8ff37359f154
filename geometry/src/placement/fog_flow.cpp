#include "kiri/geometry/placement/fog_flow.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "kiri/geometry/core/error.hpp"

namespace kiri::geometry {
namespace {

constexpr double kDrag = 1.5e-3;  // C_d of the wind on the fog's top
constexpr double kGravity = 9.81;
constexpr double kTheta = 280.0;  // K, a cool night's potential temperature

// Bilinear sample of a cell-centred field at grid coordinates (fx, fy), clamped to the grid.
template <class T>
double bilinear(const std::vector<T>& a, int nx, int ny, double fx, double fy)
{
    fx = std::clamp(fx, 0.0, double(nx - 1));
    fy = std::clamp(fy, 0.0, double(ny - 1));
    const int i = std::min(int(fx), nx - 2), j = std::min(int(fy), ny - 2);
    const double s = fx - i, t = fy - j;
    const std::size_t k = std::size_t(j) * nx + i;
    return (1 - t) * ((1 - s) * double(a[k]) + s * double(a[k + 1])) +
        t * ((1 - s) * double(a[k + nx]) + s * double(a[k + nx + 1]));
}

void check_flow_field(bool ok, const std::string& label, const char* key, const std::string& why)
{
    if (!ok)
        throw InputError(label, std::string("flow/") + key, why);
}

glm::dvec2 wind_direction(const FlowOptions& o)
{
    const double speed = glm::length(o.wind);
    return speed > 0.0 ? o.wind / speed : glm::dvec2(0.0);
}

// The pool's set-up: its top rises along the wind by slope * distance from the centroid.
double along(const Heightfield& hf, const FlowPool& p, const FlowOptions& o, std::uint32_t k)
{
    const glm::dvec2 w = wind_direction(o);
    const int i = int(k % std::uint32_t(hf.nx)), j = int(k / std::uint32_t(hf.nx));
    return p.slope * glm::dot(glm::dvec2(hf.x_of(i), hf.y_of(j)) - p.centroid, w);
}

double setup_slope(const Heightfield& hf, const FlowPool& p, const FlowOptions& o)
{
    const double depth = p.cells.empty() ? 0.0 : p.volume / (double(p.cells.size()) * hf.dx * hf.dy);
    const double reduced_gravity = kGravity * o.inversion_strength / kTheta;
    const double speed = glm::length(o.wind);
    if (!(depth > 0.0) || !(reduced_gravity > 0.0))
        return 0.0;
    return kDrag * speed * speed / (reduced_gravity * depth);
}

// The level (top at the centroid) whose plane holds the pool's volume over its cells:
// sum max(0, level + tilt_k - ground_k) dA = volume. Newton on this convex piecewise-linear
// function ends on the exact piece (each update is that piece's solution).
double solve_level(const Heightfield& hf, const FlowPool& p, const FlowOptions& o)
{
    const double a = hf.dx * hf.dy;
    double lowest = INFINITY;
    for (std::uint32_t k : p.cells)
        lowest = std::min(lowest, hf.z[k] - along(hf, p, o, k));
    if (!(p.volume > 0.0) || p.cells.empty())
        return p.cells.empty() ? 0.0 : lowest;
    double level = lowest + p.volume / a;  // at or above the root: Newton then descends to it
    for (int it = 0; it < 200; ++it) {
        double sum = 0.0;
        std::size_t count = 0;
        for (std::uint32_t k : p.cells) {
            const double key = hf.z[k] - along(hf, p, o, k);
            if (key < level) {
                sum += key;
                ++count;
            }
        }
        const double next = (p.volume / a + sum) / double(count);
        if (next == level)
            break;
        level = next;
    }
    return level;
}

}  // namespace

FlowState make_flow_state(const Heightfield& hf, const FogColumns& fog, const FlowOptions& o, const std::string& label)
{
    check_flow_field(std::isfinite(o.wind.x) && std::isfinite(o.wind.y) && glm::length(o.wind) <= 100.0, label, "wind",
                     "must be a finite wind of at most 100 m/s");
    check_flow_field(o.duration >= 0.0 && o.duration <= 30 * 86400.0, label, "duration",
                     "must be in [0, 2592000] seconds");
    check_flow_field(o.time_step > 0.0 && o.time_step <= 86400.0, label, "time_step", "must be in (0, 86400] seconds");
    check_flow_field(o.duration / o.time_step <= 1e6, label, "time_step", "more than a million steps");
    check_flow_field(o.coupling >= 0.0 && o.coupling <= 1.0, label, "coupling", "must be in [0, 1]");
    check_flow_field(o.inversion_strength > 0.0 && o.inversion_strength <= 50.0, label, "inversion_strength",
                     "must be in (0, 50] K");
    check_flow_field(o.spread >= 0.0 && std::isfinite(o.spread), label, "spread", "must be a finite number >= 0 (m/s)");
    check_flow_field(o.max_speed > 0.0 && o.max_speed <= 100.0, label, "max_speed", "must be in (0, 100] m/s");
    check_flow_field(o.evaporation_depth >= 0.0 && std::isfinite(o.evaporation_depth), label, "evaporation_depth",
                     "must be a finite number >= 0 (metres; 0 = no evaporation)");
    check_flow_field(o.min_thickness >= 0.0 && std::isfinite(o.min_thickness), label, "min_thickness",
                     "must be >= 0 (m)");
    if (fog.nx != hf.nx || fog.ny != hf.ny || fog.mask.size() != hf.size())
        throw InputError(label, "flow", "the fog columns are not on the terrain's grid");

    const int nx = hf.nx, ny = hf.ny;
    const double a = hf.dx * hf.dy;
    FlowState st;
    st.pool_of.assign(hf.size(), 0);
    st.stream.assign(hf.size(), 0.0);
    std::vector<std::uint32_t> stack;
    for (std::size_t s = 0; s < hf.size(); ++s) {
        if (!fog.mask[s] || st.pool_of[s])
            continue;
        FlowPool p;
        const std::uint32_t id = std::uint32_t(st.pools.size() + 1);
        st.pool_of[s] = id;
        stack.assign(1, std::uint32_t(s));
        while (!stack.empty()) {
            const std::uint32_t k = stack.back();
            stack.pop_back();
            p.cells.push_back(k);
            const int i = int(k % std::uint32_t(nx)), j = int(k / std::uint32_t(nx));
            for (int b = std::max(0, j - 1); b <= std::min(ny - 1, j + 1); ++b)
                for (int c = std::max(0, i - 1); c <= std::min(nx - 1, i + 1); ++c) {
                    const std::size_t n = std::size_t(b) * nx + c;
                    if (fog.mask[n] && !st.pool_of[n]) {
                        st.pool_of[n] = id;
                        stack.push_back(std::uint32_t(n));
                    }
                }
        }
        std::sort(p.cells.begin(), p.cells.end());
        for (std::uint32_t k : p.cells) {
            p.volume += fog.thickness(k) * a;
            p.centroid += glm::dvec2(hf.x_of(int(k % std::uint32_t(nx))), hf.y_of(int(k / std::uint32_t(nx))));
        }
        p.centroid /= double(p.cells.size());
        st.pools.push_back(std::move(p));
    }
    // Rims: cells outside every pool next to one (sorted, so the steps run in a fixed order).
    for (std::size_t q = 0; q < st.pools.size(); ++q) {
        FlowPool& p = st.pools[q];
        for (std::uint32_t k : p.cells) {
            const int i = int(k % std::uint32_t(nx)), j = int(k / std::uint32_t(nx));
            for (int b = std::max(0, j - 1); b <= std::min(ny - 1, j + 1); ++b)
                for (int c = std::max(0, i - 1); c <= std::min(nx - 1, i + 1); ++c) {
                    const std::size_t n = std::size_t(b) * nx + c;
                    if (!st.pool_of[n])
                        p.rim.push_back(std::uint32_t(n));
                }
        }
        std::sort(p.rim.begin(), p.rim.end());
        p.rim.erase(std::unique(p.rim.begin(), p.rim.end()), p.rim.end());
        p.slope = setup_slope(hf, p, o);
        p.level = solve_level(hf, p, o);
    }
    // The stream's velocity: a share of the wind, and gravity down the terrain.
    st.u.resize(hf.size());
    st.v.resize(hf.size());
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const int i0 = std::max(0, i - 1), i1 = std::min(nx - 1, i + 1);
            const int j0 = std::max(0, j - 1), j1 = std::min(ny - 1, j + 1);
            const glm::dvec2 grad((hf.at(i1, j) - hf.at(i0, j)) / ((i1 - i0) * hf.dx),
                                  (hf.at(i, j1) - hf.at(i, j0)) / ((j1 - j0) * hf.dy));
            const double slope = glm::length(grad);
            glm::dvec2 vel = o.coupling * o.wind;
            if (slope > 0.0)
                vel -= std::min(o.max_speed, o.spread * slope) * grad / slope;
            st.u[std::size_t(j) * nx + i] = float(vel.x);
            st.v[std::size_t(j) * nx + i] = float(vel.y);
        }
    return st;
}

void flow_step(const Heightfield& hf, FlowState& st, const FlowOptions& o, double dt)
{
    const int nx = hf.nx, ny = hf.ny;
    const double a = hf.dx * hf.dy, cell = std::min(hf.dx, hf.dy);
    const double speed = glm::length(o.wind);
    // (1) + (2): levels, then spills over the rims.
    for (FlowPool& p : st.pools) {
        p.slope = setup_slope(hf, p, o);
        p.level = solve_level(hf, p, o);
        for (std::uint32_t k : p.rim) {
            const double top = p.level + along(hf, p, o, k);
            st.max_tilt_m = std::max(st.max_tilt_m, top - p.level);
            const double above = top - hf.z[k];
            if (above <= 0.0 || p.volume <= 0.0)
                continue;
            const double spill = std::min(above * o.coupling * speed * dt / cell, p.volume / a);
            st.stream[k] += spill;
            p.volume -= spill * a;
            st.spilled_m3 += spill * a;
        }
    }
    // (3) The stream, forward semi-Lagrangian. It evaporates as it sinks below the inversion
    // (the highest pool top): run-up on a windward shore sliding back does not, a fall down a
    // lee slope below the pools' top does.
    double inversion = -INFINITY;
    for (const FlowPool& p : st.pools)
        inversion = std::max(inversion, p.level);
    st.next.assign(hf.size(), 0.0);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const std::size_t k = std::size_t(j) * nx + i;
            double m = st.stream[k];
            if (m <= 0.0)
                continue;
            double fx = i, fy = j;
            const double own = std::hypot(double(st.u[k]), double(st.v[k]));
            const int subs = std::clamp(int(std::ceil(own * dt / cell)), 1, 64);
            const double sdt = dt / subs;
            double descent = 0.0, ground = hf.z[k];
            for (int s = 0; s < subs; ++s) {
                const double du = bilinear(st.u, nx, ny, fx, fy), dv = bilinear(st.v, nx, ny, fx, fy);
                fx += du * sdt / hf.dx;
                fy += dv * sdt / hf.dy;
                const double here = bilinear(hf.z, nx, ny, fx, fy);
                descent += std::max(0.0, std::min(ground, inversion) - std::min(here, inversion));
                ground = here;
            }
            if (o.evaporation_depth > 0.0 && descent > 0.0) {
                const double kept = m * std::exp(-descent / o.evaporation_depth);
                st.evaporated_m3 += (m - kept) * a;
                m = kept;
            }
            const double ffx = std::floor(fx), ffy = std::floor(fy);
            const double s = fx - ffx, t = fy - ffy;
            const int ci = int(ffx), cj = int(ffy);
            const double w[4] = {(1 - s) * (1 - t), s * (1 - t), (1 - s) * t, s * t};
            const int di[4] = {0, 1, 0, 1}, dj[4] = {0, 0, 1, 1};
            for (int c = 0; c < 4; ++c) {
                if (w[c] == 0.0)
                    continue;
                const int ii = ci + di[c], jj = cj + dj[c];
                if (ii < 0 || jj < 0 || ii >= nx || jj >= ny)
                    st.outflow_m3 += w[c] * m * a;
                else
                    st.next[std::size_t(jj) * nx + ii] += w[c] * m;
            }
        }
    // (3b) The stream's own weight: where it piles up (in a pit, against a slope) the part of a
    // column above a neighbour's surface spreads to it, as long as the ground drops less than
    // the column is thick (thin fog on a slope is the advection's business). A tenth of each
    // difference a sweep: conservative, never negative, whatever dt.
    for (int sweep = 0; sweep < 4; ++sweep) {
        st.moved.assign(hf.size(), 0.0);
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const std::size_t k = std::size_t(j) * nx + i;
                const double hk = st.next[k];
                if (hk <= 0.0)
                    continue;
                const double eta = hf.z[k] + hk;
                double give[9], total = 0.0;
                int q = 0;
                for (int b = j - 1; b <= j + 1; ++b)
                    for (int c = i - 1; c <= i + 1; ++c, ++q) {
                        give[q] = 0.0;
                        if ((b == j && c == i) || b < 0 || c < 0 || b >= ny || c >= nx)
                            continue;
                        const std::size_t n = std::size_t(b) * nx + c;
                        if (hf.z[k] - hf.z[n] >= hk)
                            continue;
                        give[q] = std::max(0.0, eta - hf.z[n] - st.next[n]) * 0.1;
                        total += give[q];
                    }
                if (total <= 0.0)
                    continue;
                const double scale = total > hk ? hk / total : 1.0;
                q = 0;
                for (int b = j - 1; b <= j + 1; ++b)
                    for (int c = i - 1; c <= i + 1; ++c, ++q) {
                        if (give[q] <= 0.0)
                            continue;
                        const std::size_t n = std::size_t(b) * nx + c;
                        const double g = give[q] * scale;
                        st.moved[k] -= g;
                        double kept = g;
                        const double sink = std::min(hf.z[k], inversion) - std::min(hf.z[n], inversion);
                        if (o.evaporation_depth > 0.0 && sink > 0.0) {
                            kept = g * std::exp(-sink / o.evaporation_depth);
                            st.evaporated_m3 += (g - kept) * a;
                        }
                        st.moved[n] += kept;
                    }
            }
        for (std::size_t k = 0; k < st.next.size(); ++k)
            st.next[k] = std::max(0.0, st.next[k] + st.moved[k]);
    }
    // (4) What lands in a pool joins it.
    for (std::size_t k = 0; k < st.next.size(); ++k)
        if (st.pool_of[k] && st.next[k] > 0.0) {
            st.pools[st.pool_of[k] - 1].volume += st.next[k] * a;
            st.next[k] = 0.0;
        }
    st.stream.swap(st.next);
}

std::vector<double> flow_thickness(const Heightfield& hf, const FlowState& st, const FlowOptions& o)
{
    std::vector<double> h = st.stream;
    for (const FlowPool& pool : st.pools) {
        FlowPool p = pool;
        p.slope = setup_slope(hf, p, o);
        p.level = solve_level(hf, p, o);
        for (std::uint32_t k : p.cells)
            h[k] += std::max(0.0, p.level + along(hf, p, o, k) - hf.z[k]);
    }
    return h;
}

FogColumns flow_fog(const Heightfield& hf, const FogColumns& fog, const FlowOptions& o, FlowReport* report,
                    const std::string& label)
{
    FlowState st = make_flow_state(hf, fog, o, label);
    FlowReport rep;
    rep.pools = int(st.pools.size());
    for (const FlowPool& p : st.pools)
        rep.volume_before_m3 += p.volume;
    for (double t = 0.0; t < o.duration - 1e-9; t += o.time_step, ++rep.steps)
        flow_step(hf, st, o, std::min(o.time_step, o.duration - t));
    const std::vector<double> h = flow_thickness(hf, st, o);
    const double a = hf.dx * hf.dy;
    FogColumns out;
    out.nx = hf.nx;
    out.ny = hf.ny;
    out.mask.assign(hf.size(), 0);
    out.bottom = hf.z;
    out.top = hf.z;
    for (std::size_t k = 0; k < h.size(); ++k) {
        rep.volume_after_m3 += h[k] * a;
        rep.stream_m3 += st.stream[k] * a;
        if (h[k] > o.min_thickness) {
            out.mask[k] = 1;
            out.top[k] = hf.z[k] + h[k];
        }
    }
    rep.outflow_m3 = st.outflow_m3;
    rep.evaporated_m3 = st.evaporated_m3;
    rep.spilled_m3 = st.spilled_m3;
    rep.max_tilt_m = st.max_tilt_m;
    rep.evaporation_depth_m = o.evaporation_depth;
    if (report)
        *report = rep;
    return out;
}

}  // namespace kiri::geometry
