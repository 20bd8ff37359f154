#include "kiri/geometry/reference/path_tracer.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include <glm/geometric.hpp>

#include "reference/path_tracer_core.hpp"
#include "reference/terrain_shading.hpp"

namespace kiri::geometry {
namespace {

using detail::around;
using detail::Random;
using detail::sample_phase;

// Where a ray that meets nothing ends (as the reference's sky rays).
constexpr double far_distance = 1e6;
// Ratio tracking rolls the dice once the transmittance estimate falls below this.
constexpr double transmittance_roulette = 0.05;

double finite_or(double v, double fallback) { return std::isfinite(v) ? v : fallback; }
glm::dvec3 finite_or_zero(const glm::dvec3& v)
{
    return {finite_or(v.x, 0.0), finite_or(v.y, 0.0), finite_or(v.z, 0.0)};
}
double clamp_g(double g) { return std::isfinite(g) ? std::clamp(g, -0.999, 0.999) : 0.0; }
double clamp_albedo(double a) { return std::isfinite(a) ? std::clamp(a, 0.0, 1.0) : 0.0; }

// Cosine-weighted about the normal n: the Lambertian bounce (weight = albedo).
glm::dvec3 sample_cosine(const glm::dvec3& n, Random& rng)
{
    const double u = rng.uniform(), phi = 2.0 * std::numbers::pi * rng.uniform();
    return around(n, std::sqrt(1.0 - u), phi);
}

}  // namespace

namespace detail {

PathTracer::PathTracer(const FogVolume& fog, const Heightfield* terrain, const FogLighting& light,
                       const PathTracerOptions& options)
{
    if (fog.medium && fog.medium->max_extinction() > 0.0 && std::isfinite(fog.medium->max_extinction())) {
        medium_ = fog.medium;
        const Medium& m = *medium_;
        const MediumGrid& g = m.grid();
        frame_ = {g.x0, g.y0, g.dx, g.dy, g.nx, g.ny};
        z_lo_ = m.bounds().min.z;
        z_hi_ = m.bounds().max.z;
        albedo_medium_ = clamp_albedo(m.options().albedo);
        g_medium_ = clamp_g(m.options().anisotropy);
        // density <= coverage * profile * detail * dissipation, each factor's largest value;
        // and inside the shell >= each factor's smallest (detail in [0, 1], dissipation
        // smallest at the top).
        const double detail = std::isfinite(m.detail().detail) ? m.detail().detail : 0.0;
        const double bound =
            m.options().extinction * std::max(1.0, m.options().top_density) * std::max(1.0, 1.0 - detail);
        const double floor_bound = detail >= 0.0 && detail <= 1.0 && m.options().top_density >= 0.0
            ? m.options().extinction * std::min(1.0, m.options().top_density) * (1.0 - detail) * m.dissipation(1.0)
            : 0.0;
        cells_.resize(std::size_t(g.nx - 1) * std::size_t(g.ny - 1));
        for (int j = 0; j + 1 < g.ny; ++j)
            for (int i = 0; i + 1 < g.nx; ++i) {
                const std::size_t k[4] = {std::size_t(j) * g.nx + i, std::size_t(j) * g.nx + i + 1,
                                          std::size_t(j + 1) * g.nx + i, std::size_t(j + 1) * g.nx + i + 1};
                double cover = 0.0, least_cover = inf, lo = inf, hi = -inf, core_lo = -inf, core_hi = inf,
                       thinnest = inf;
                for (std::size_t c : k) {
                    cover = std::max(cover, g.coverage[c]);
                    least_cover = std::min(least_cover, g.coverage[c]);
                    lo = std::min(lo, g.floor[c]);
                    hi = std::max(hi, g.top[c]);
                    core_lo = std::max(core_lo, g.floor[c]);
                    core_hi = std::min(core_hi, g.top[c]);
                    thinnest = std::min(thinnest, g.top[c] - g.bottom[c]);
                }
                MajorantCell& cell = cells_[std::size_t(j) * std::size_t(g.nx - 1) + std::size_t(i)];
                if (cover > 0.0 && hi > lo) {
                    cell.sigma = bound * cover;
                    cell.z_lo = lo;
                    cell.z_hi = hi;
                    if (least_cover > 0.0 && thinnest > 0.0 && core_hi > core_lo && floor_bound > 0.0) {
                        cell.control = std::min(floor_bound * least_cover, cell.sigma);
                        cell.core_lo = core_lo;
                        cell.core_hi = core_hi;
                    }
                }
            }
    }
    haze_ = fog.height_fog;
    haze_on_ = haze_.enabled() && std::isfinite(haze_.extinction) && haze_.scale_height > 0.0 &&
        std::isfinite(haze_.scale_height) && std::isfinite(haze_.base);
    albedo_haze_ = clamp_albedo(haze_.albedo);
    g_haze_ = clamp_g(haze_.anisotropy);
    if (terrain && terrain->nx >= 2 && terrain->ny >= 2 && terrain->z.size() == std::size_t(terrain->nx) * terrain->ny)
        terrain_ = std::make_unique<HeightfieldRay>(*terrain, options.surround);
    const double len = glm::length(light.sun_direction);
    sun_ = len > 0.0 && std::isfinite(len) ? light.sun_direction / len : glm::dvec3(0.0, 0.0, 1.0);
    sun_radiance_ = glm::max(finite_or_zero(light.sun_radiance), glm::dvec3(0.0));
    ambient_ = light.sky ? glm::max(finite_or_zero(light.ambient), glm::dvec3(0.0)) : glm::dvec3(0.0);
    sun_on_ = sun_radiance_.x > 0.0 || sun_radiance_.y > 0.0 || sun_radiance_.z > 0.0;
    terrain_shadows_ = light.terrain_shadows;
    fog_shadows_ = light.fog_shadows;
    sky_ = light.sky ? options.sky : PathSky::none;
    lambertian_ = options.ground == PathGround::lambertian;
    max_bounces_ = std::clamp(options.max_bounces, 0, 1 << 20);
    roulette_after_ = std::max(options.roulette_after, 0);
}

template <class Visit>
void PathTracer::walk_cells(const glm::dvec3& o, const glm::dvec3& w, double t0, double t1, Visit&& visit) const
{
    if (!clip_slab(o.z, w.z, z_lo_, z_hi_, t0, t1))
        return;
    const std::size_t row = std::size_t(frame_.nx - 1);
    walk_grid(frame_, o, w, t0, t1, [&](int i, int j, double ta, double tb) {
        const MajorantCell& cell = cells_[std::size_t(j) * row + std::size_t(i)];
        if (!(cell.sigma > 0.0) || !clip_slab(o.z, w.z, cell.z_lo, cell.z_hi, ta, tb) || !(tb > ta))
            return true;
        return visit(cell, ta, tb);
    });
}

double PathTracer::medium_collision(const glm::dvec3& o, const glm::dvec3& w, double t1, Random& rng) const
{
    // Delta tracking [Woodcock65]: tentative collisions at the cell's majorant rate, each real
    // with probability sigma_t / majorant.
    double hit = inf;
    walk_cells(o, w, 0.0, t1, [&](const MajorantCell& cell, double a, double b) {
        double t = a;
        for (;;) {
            t -= std::log1p(-rng.uniform()) / cell.sigma;
            if (!(t < b))
                return true;
            if (rng.uniform() * cell.sigma < medium_->extinction(o + w * t)) {
                hit = t;
                return false;
            }
        }
    });
    return hit;
}

double PathTracer::medium_transmittance(const glm::dvec3& o, const glm::dvec3& w, Random& rng) const
{
    // Residual ratio tracking [Novak14]: in a cell's core (wholly inside the shell) the control
    // extinction's transmittance exactly, times the product of (1 - (sigma_t - control) / rate)
    // over tentative collisions at the residual's majorant rate; elsewhere plain ratio tracking.
    // Russian roulette once the estimate is small. (In a uniform slab the control is the
    // extinction itself: the sun's transmittance is exact.)
    double transmittance = 1.0;
    auto track = [&](double a, double b, double control, double majorant) {
        if (control > 0.0)
            transmittance *= std::exp(-control * (b - a));
        const double rate = majorant - control;
        if (!(rate > 0.0))
            return true;
        for (double t = a;;) {
            t -= std::log1p(-rng.uniform()) / rate;
            if (!(t < b))
                return true;
            transmittance *= 1.0 - std::clamp((medium_->extinction(o + w * t) - control) / rate, 0.0, 1.0);
            if (transmittance < transmittance_roulette) {
                if (rng.uniform() * transmittance_roulette >= transmittance) {
                    transmittance = 0.0;
                    return false;
                }
                transmittance = transmittance_roulette;
            }
        }
    };
    walk_cells(o, w, 0.0, inf, [&](const MajorantCell& cell, double a, double b) {
        double c0 = a, c1 = b;
        if (!(cell.control > 0.0) || !clip_slab(o.z, w.z, cell.core_lo, cell.core_hi, c0, c1) || !(c1 > c0))
            return track(a, b, 0.0, cell.sigma);
        return track(a, c0, 0.0, cell.sigma) && track(c0, c1, cell.control, cell.sigma) &&
            track(c1, b, 0.0, cell.sigma);
    });
    return transmittance;
}

double PathTracer::haze_collision(const glm::dvec3& o, const glm::dvec3& w, double t1, Random& rng) const
{
    // The free path of the height fog alone, exactly: the t where its optical depth from o
    // reaches an exponential variate, by the closed form's inverse.
    const double target = -std::log1p(-rng.uniform());
    return haze_.free_path(o, w, 0.0, t1, target);
}

double PathTracer::sun_transmittance(const glm::dvec3& p, Random& rng) const
{
    if (terrain_shadows_ && terrain_ && terrain_->first_hit(p, sun_, 0.0, inf))
        return 0.0;
    if (!fog_shadows_)
        return 1.0;
    double transmittance = haze_on_ ? std::exp(-haze_.optical_depth(p, sun_, 0.0, inf)) : 1.0;
    if (transmittance > 0.0 && medium_)
        transmittance *= medium_transmittance(p, sun_, rng);
    return transmittance;
}

glm::dvec3 PathTracer::sky(const glm::dvec3& w) const
{
    switch (sky_) {
    case PathSky::sphere: return ambient_;
    case PathSky::hemisphere: return w.z > 0.0 ? ambient_ : glm::dvec3(0.0);
    case PathSky::none: break;
    }
    return glm::dvec3(0.0);
}

glm::dvec3 PathTracer::sample(const glm::dvec3& origin, const glm::dvec3& dir, double t_max, Random& rng,
                              long long& vertices) const
{
    glm::dvec3 radiance(0.0), throughput(1.0);
    glm::dvec3 o = origin, w = dir;
    double t_limit = std::isfinite(t_max) && t_max > 0.0 ? t_max : far_distance;
    for (int vertex = 0;;) {
        double t_end = t_limit;
        bool ground = false;
        if (terrain_)
            if (const auto hit = terrain_->first_hit(o, w, 0.0, t_end)) {
                t_end = *hit;
                ground = true;
            }
        double t = medium_ ? medium_collision(o, w, t_end, rng) : inf;
        bool in_haze = false;
        if (haze_on_) {
            const double th = haze_collision(o, w, std::min(t, t_end), rng);
            if (th < t) {
                t = th;
                in_haze = true;
            }
        }
        if (t < t_end) {  // scattered in the fog
            if (vertex >= max_bounces_)
                break;
            ++vertex;
            ++vertices;
            const double g = in_haze ? g_haze_ : g_medium_;
            throughput *= in_haze ? albedo_haze_ : albedo_medium_;
            const glm::dvec3 p = o + w * t;
            // The sun's irradiance pi sun, scattered towards -w by the phase function.
            if (sun_on_)
                if (const double ts = sun_transmittance(p, rng); ts > 0.0)
                    radiance +=
                        throughput * sun_radiance_ * (std::numbers::pi * henyey_greenstein(glm::dot(w, sun_), g) * ts);
            w = sample_phase(w, g, rng);
            o = p;
        } else if (ground) {
            if (!lambertian_ || vertex >= max_bounces_)
                break;
            ++vertex;
            ++vertices;
            const glm::dvec3 p = o + w * t_end;
            const glm::dvec3 n = terrain_->normal(p.x, p.y);
            throughput *= ground_albedo(terrain_->ground(), p, n);
            const glm::dvec3 q = p + n * (0.01 + 1e-7 * glm::length(p));  // off the surface's own triangles
            // Lambert: albedo / pi times the sun's irradiance pi sun cos.
            if (const double c = glm::dot(n, sun_); sun_on_ && c > 0.0)
                if (const double ts = sun_transmittance(q, rng); ts > 0.0)
                    radiance += throughput * sun_radiance_ * (c * ts);
            w = sample_cosine(n, rng);
            o = q;
        } else {  // left the scene
            radiance += throughput * sky(w);
            break;
        }
        t_limit = far_distance;
        if (!(throughput.x > 0.0 || throughput.y > 0.0 || throughput.z > 0.0))
            break;  // absorbed
        if (vertex >= roulette_after_) {
            const double survive = std::min(1.0, std::max({throughput.x, throughput.y, throughput.z}));
            if (!(survive > 0.0) || rng.uniform() >= survive)
                break;
            throughput /= survive;
        }
    }
    return radiance;
}

}  // namespace detail

}  // namespace kiri::geometry
