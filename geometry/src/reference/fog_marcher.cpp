#include "reference/fog_marcher.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "kiri/geometry/medium/light_volume.hpp"
#include "reference/grid_walk.hpp"
#include "reference/terrain_shading.hpp"

namespace kiri::geometry::detail {
namespace {

// Two-point Gauss-Legendre nodes on [0, 1]: exact for cubics.
constexpr double gauss_lo = 0.5 - 0.28867513459481288225, gauss_hi = 0.5 + 0.28867513459481288225;
// The layers' per-layer shift of the noise (medium.cpp, layers.frag): how fast the noise
// changes with height inside the shell, for the step control only.
constexpr double noise_shift_x = 0.137, noise_shift_y = 0.071;
constexpr int noise_texels = 256;

// In-scattering of one step with constant coefficients: integral_0^dt exp(-sigma t) dt.
double step_weight(double sigma, double dt)
{
    const double x = sigma * dt;
    return x > 1e-6 ? -std::expm1(-x) / sigma : dt * (1.0 - 0.5 * x);
}

}  // namespace

FogMarcher::FogMarcher(const FogVolume& fog, const Heightfield* terrain, const FogLighting& light,
                       const ReferenceOptions& o)
    : fog_(fog), heightfield_(terrain), light_(light), o_(o)
{
    if (terrain && terrain->nx >= 2 && terrain->ny >= 2)
        terrain_ = std::make_unique<HeightfieldRay>(*terrain, o.surround);
    const double len = glm::length(light.sun_direction);
    sun_ = len > 0.0 && std::isfinite(len) ? light.sun_direction / len : glm::dvec3(0.0, 0.0, 1.0);
    if (!light_.sky) {
        light_.ambient = glm::dvec3(0.0);
        light_.air = {};
    }
    if (fog_.medium && !(fog_.medium->max_extinction() > 0.0))
        fog_.medium = nullptr;
    o_.optical_step = std::clamp(o_.optical_step, 1e-4, 1.0);
    o_.shadow_optical_step = std::clamp(o_.shadow_optical_step, 1e-4, 1.0);
    o_.knot_optical_step = std::clamp(o_.knot_optical_step, 1e-4, 1.0);
    o_.feature_fraction = std::clamp(o_.feature_fraction, 1e-3, 4.0);
    o_.shadow_feature_fraction = std::clamp(o_.shadow_feature_fraction, 1e-3, 16.0);
    sun_decay_ = sun_scattering_decay(light_.multiple_scattering, light_.scattering_octaves, light_.fit);
    sun_cutoff_ = o_.sun_cutoff / sun_decay_;
}

double FogMarcher::feature_length(const glm::dvec3& p, const glm::dvec3& d, bool in_shell, double fraction) const
{
    double len = inf;
    if (in_shell && fog_.medium) {
        const MediumGrid& g = fog_.medium->grid();
        const double dxy = std::hypot(d.x, d.y);
        if (dxy > 0.0)
            len = std::min(len, fraction * std::min(g.dx, g.dy) / dxy);
        const MediumDetail& det = fog_.medium->detail();
        if (det.detail > 0.0) {
            const MediumColumn c = fog_.medium->column(p.x, p.y);
            const double thick = std::max(c.top - c.bottom, 1e-6), tile = 8.0 * det.detail_scale;
            const double a = d.x / tile + d.z * det.layers * noise_shift_x / thick;
            const double b = d.y / tile + d.z * det.layers * noise_shift_y / thick;
            const double rate = noise_texels * std::hypot(a, b);  // texels per metre
            if (rate > 0.0)
                len = std::min(len, fraction / rate);
        }
    }
    if (fog_.height_fog.enabled() && d.z != 0.0)
        len = std::min(len, fraction * fog_.height_fog.scale_height / std::abs(d.z));
    return len;
}

void FogMarcher::march_view(const glm::dvec3& o, const glm::dvec3& w, double t_end, MarchScratch& s) const
{
    s.steps.clear();
    if (fog_.medium)
        shell_intervals(*fog_.medium, o, w, 0.0, t_end, s.view_intervals);
    else
        s.view_intervals.clear();
    const bool haze = fog_.height_fog.enabled();
    const double tau_stop = -std::log(std::max(o_.min_transmittance, 1e-300));
    double tau = 0.0;
    auto piece = [&](double a, double b, bool in_shell) {
        double t = a;
        auto sigma_at = [&](double u) {
            const glm::dvec3 p = o + w * u;
            return (in_shell ? sigma_medium(p) : 0.0) + fog_.height_fog.sigma(p);
        };
        double sigma_estimate = sigma_at(a + 1e-9 * (b - a));
        while (t < b) {
            const glm::dvec3 p = o + w * t;
            double dt = std::min({feature_length(p, w, in_shell, o_.feature_fraction),
                                  o_.optical_step / std::max(sigma_estimate, 1e-12), b - t});
            dt = std::max(dt, 1e-7 * (1.0 + t));
            if (t + dt > b || b - (t + dt) < 1e-9 * dt)
                dt = b - t;
            double sm = 0.0;
            if (in_shell) {
                const double s1 = sigma_medium(o + w * (t + gauss_lo * dt)),
                             s2 = sigma_medium(o + w * (t + gauss_hi * dt));
                sm = 0.5 * (s1 + s2);
                sigma_estimate = std::max(s1, s2);
            } else {
                sigma_estimate = 0.0;
            }
            const double sh = haze ? fog_.height_fog.optical_depth(o, w, t, t + dt) / dt : 0.0;
            sigma_estimate += haze ? std::max(fog_.height_fog.sigma(p), fog_.height_fog.sigma(p + w * dt)) : 0.0;
            s.steps.push_back({t + 0.5 * dt, dt, sm, sh, tau});
            tau += (sm + sh) * dt;
            t += dt;
            if (tau > tau_stop)
                return false;
        }
        return true;
    };
    if (!haze) {
        for (const Interval& iv : s.view_intervals)
            if (!piece(iv.t0, iv.t1, true))
                return;
        return;
    }
    // The height fog alone only over its extent.
    double lo = 0.0, hi = t_end;
    const HeightFog& h = fog_.height_fog;
    if (!clip_slab(o.x, w.x, h.min.x, h.max.x, lo, hi) || !clip_slab(o.y, w.y, h.min.y, h.max.y, lo, hi))
        hi = lo = t_end;
    auto haze_only = [&](double a, double b) {
        a = std::max(a, lo);
        b = std::min(b, hi);
        return !(b > a) || piece(a, b, false);
    };
    double cursor = 0.0;
    for (const Interval& iv : s.view_intervals) {
        if (iv.t0 > cursor && !haze_only(cursor, iv.t0))
            return;
        if (!piece(iv.t0, iv.t1, true))
            return;
        cursor = iv.t1;
    }
    if (t_end > cursor)
        haze_only(cursor, t_end);
}

bool FogMarcher::sun_visible(const glm::dvec3& p) const
{
    if (!light_.terrain_shadows || !terrain_)
        return true;
    return !terrain_->first_hit(p, sun_, 0.0, inf).has_value();
}

double FogMarcher::sun_optical_depth(const glm::dvec3& p, MarchScratch& s) const
{
    if (!light_.fog_shadows)
        return 0.0;
    double tau = fog_.height_fog.optical_depth(p, sun_, 0.0, inf);
    if (!fog_.medium || !(tau <= sun_cutoff_))
        return tau;
    const Bounds3& b = fog_.medium->bounds();
    double t0 = 0.0, t1 = inf;
    if (!clip_slab(p.x, sun_.x, b.min.x, b.max.x, t0, t1) || !clip_slab(p.y, sun_.y, b.min.y, b.max.y, t0, t1) ||
        !clip_slab(p.z, sun_.z, b.min.z, b.max.z, t0, t1) || std::isinf(t1))
        return tau;
    shell_intervals(*fog_.medium, p, sun_, t0, t1, s.sun_intervals);
    for (const Interval& iv : s.sun_intervals) {
        double t = iv.t0;
        double sigma_estimate = sigma_medium(p + sun_ * (t + 1e-9 * (iv.t1 - iv.t0)));
        while (t < iv.t1) {
            const glm::dvec3 q = p + sun_ * t;
            // Past sun_cutoff the light left falls as e^-(decay tau): steps as long in that.
            const double optical_step = o_.shadow_optical_step / (tau < o_.sun_cutoff ? 1.0 : sun_decay_);
            double dt = std::min({feature_length(q, sun_, true, o_.shadow_feature_fraction),
                                  optical_step / std::max(sigma_estimate, 1e-12), iv.t1 - t});
            dt = std::max(dt, 1e-7 * (1.0 + t));
            if (t + dt > iv.t1 || iv.t1 - (t + dt) < 1e-9 * dt)
                dt = iv.t1 - t;
            const double s1 = sigma_medium(p + sun_ * (t + gauss_lo * dt)),
                         s2 = sigma_medium(p + sun_ * (t + gauss_hi * dt));
            tau += 0.5 * (s1 + s2) * dt;
            sigma_estimate = std::max(s1, s2);
            t += dt;
            if (tau > sun_cutoff_)
                return tau;
        }
    }
    return tau;
}

SunKnot FogMarcher::sun_knot(const glm::dvec3& o, const glm::dvec3& w, double t, MarchScratch& s) const
{
    SunKnot k;
    k.t = t;
    const glm::dvec3 p = o + w * t;
    k.visible = sun_visible(p);
    k.tau = k.visible ? sun_optical_depth(p, s) : 0.0;
    return k;
}

void FogMarcher::place_knots(const glm::dvec3& o, const glm::dvec3& w, MarchScratch& s) const
{
    s.knots.clear();
    if (s.steps.empty())
        return;
    const bool haze = fog_.height_fog.enabled();
    double last_t = -inf, last_tau = -inf;
    for (std::size_t i = 0; i < s.steps.size(); ++i) {
        const MarchStep& st = s.steps[i];
        // Knots where the view ray has crossed knot_optical_step of optical depth or a grid
        // cell (or a quarter scale height of haze) since the last one, and at both ends.
        double spacing = inf;
        if (fog_.medium) {
            const MediumGrid& g = fog_.medium->grid();
            const double dxy = std::hypot(w.x, w.y);
            if (dxy > 0.0)
                spacing = std::min(g.dx, g.dy) / dxy;
        }
        if (haze && w.z != 0.0)
            spacing = std::min(spacing, 0.25 * fog_.height_fog.scale_height / std::abs(w.z));
        const bool due = i == 0 || i + 1 == s.steps.size() || st.tau_before - last_tau >= o_.knot_optical_step ||
            st.t - last_t >= spacing;
        if (!due)
            continue;
        s.knots.push_back(sun_knot(o, w, st.t, s));
        last_t = st.t;
        last_tau = st.tau_before;
    }
    // Terrain shadow edges between knots: bisection, then a knot on either side.
    if (!light_.terrain_shadows || !terrain_)
        return;
    for (std::size_t k = 0; k + 1 < s.knots.size(); ++k) {
        if (s.knots[k].visible == s.knots[k + 1].visible)
            continue;
        double lo = s.knots[k].t, hi = s.knots[k + 1].t;
        const bool lo_visible = s.knots[k].visible;
        for (int it = 0; it < 60 && hi - lo > 1e-6 * (1.0 + hi); ++it) {
            const double mid = 0.5 * (lo + hi);
            (sun_visible(o + w * mid) == lo_visible ? lo : hi) = mid;
        }
        SunKnot a = sun_knot(o, w, lo, s), b = sun_knot(o, w, hi, s);
        a.visible = lo_visible;  // by construction of the bisection
        b.visible = !lo_visible;
        s.knots.insert(s.knots.begin() + std::ptrdiff_t(k) + 1, {a, b});
        k += 2;
    }
}

void FogMarcher::split_at_shadow_edges(MarchScratch& s) const
{
    // The shadow edges place_knots found, in order; a step that holds one becomes two, so that
    // each step is wholly lit or wholly shadowed (its extinction stays the step's mean).
    std::size_t k = 0;
    bool any = false;
    for (std::size_t i = 0; i + 1 < s.knots.size(); ++i)
        any = any || s.knots[i].visible != s.knots[i + 1].visible;
    if (!any)
        return;
    s.split.clear();
    for (const MarchStep& st : s.steps) {
        double lo = st.t - 0.5 * st.dt;
        const double hi = st.t + 0.5 * st.dt;
        double tau = st.tau_before;
        const double sigma = st.sigma_medium + st.sigma_height;
        for (; k + 1 < s.knots.size() && 0.5 * (s.knots[k].t + s.knots[k + 1].t) < hi; ++k) {
            if (s.knots[k].visible == s.knots[k + 1].visible)
                continue;
            const double edge = 0.5 * (s.knots[k].t + s.knots[k + 1].t);
            if (edge <= lo)
                continue;
            s.split.push_back({0.5 * (lo + edge), edge - lo, st.sigma_medium, st.sigma_height, tau});
            tau += sigma * (edge - lo);
            lo = edge;
        }
        s.split.push_back({0.5 * (lo + hi), hi - lo, st.sigma_medium, st.sigma_height, tau});
    }
    s.steps.swap(s.split);
}

glm::dvec3 FogMarcher::surface_radiance(const glm::dvec3& p, MarchScratch& s, glm::dvec3* fog_shade,
                                        double* sun_through) const
{
    // render/shaders/terrain.frag before the air's haze (trace adds it), with the cast shadows
    // and the fog's shade of the sun that the lighting model adds.
    const glm::dvec3 n = terrain_->normal(p.x, p.y);
    const glm::dvec3 base = ground_albedo(terrain_->ground(), p, n);
    // The sun's transmittance even where this ground turns from the sun or lies in the
    // terrain's shadow: compare_frames dims another ground's sunlight by it.
    const glm::dvec3 q = p + n * (0.01 + 1e-7 * glm::length(p));  // off the surface's own triangles
    const double through = std::exp(-sun_optical_depth(q, s));
    double direct = std::max(glm::dot(n, sun_), 0.0);
    if (direct > 0.0 && !sun_visible(q))
        direct = 0.0;
    if (fog_shade)
        *fog_shade = base * light_.sun_radiance * (direct * (1.0 - through));
    if (sun_through)
        *sun_through = through;
    const glm::dvec3 sky = light_.ambient * (0.6 + 0.4 * n.z);
    return base * (light_.sun_radiance * (direct * through) + sky);
}

glm::dvec3 FogMarcher::sky_radiance(const glm::dvec3& w) const
{
    // render/shaders/sky.frag in linear radiance.
    if (!light_.sky)
        return glm::dvec3(0.0);
    const glm::dvec3 zenith = light_.ambient * glm::dvec3(0.9, 1.5, 2.6);
    const glm::dvec3 horizon = sky_horizon(light_.ambient);
    const double elevation = std::clamp(w.z, -1.0, 1.0);
    glm::dvec3 sky = mix(horizon, zenith, std::pow(std::max(elevation, 0.0), 0.45));
    if (elevation < 0.0)
        sky = horizon * (1.0 + 0.3 * elevation);
    const double sun = std::max(glm::dot(w, sun_), 0.0);
    return sky + light_.sun_radiance * (0.02 * std::pow(sun, 8.0) + 0.25 * std::pow(sun, 400.0));
}

RayFog FogMarcher::trace(const glm::dvec3& o, const glm::dvec3& w, double t_max, MarchScratch& s) const
{
    RayFog r;
    double t_end = std::isfinite(t_max) && t_max > 0.0 ? t_max : 1e6;
    if (terrain_)
        if (const auto hit = terrain_->first_hit(o, w, 0.0, t_end)) {
            t_end = *hit;
            r.hit_terrain = true;
        }
    r.distance = t_end;
    if (!fog_.medium && !fog_.height_fog.enabled()) {
        s.steps.clear();
    } else {
        march_view(o, w, t_end, s);
    }
    const double cos_sun = glm::dot(w, sun_);
    const double albedo_m = fog_.medium ? fog_.medium->options().albedo : 0.0;
    const double g_m = fog_.medium ? fog_.medium->options().anisotropy : 0.0;
    const double albedo_h = fog_.height_fog.albedo, g_h = fog_.height_fog.anisotropy;
    const bool sun_term = light_.fog_shadows || (light_.terrain_shadows && terrain_);
    if (sun_term) {
        place_knots(o, w, s);
        split_at_shadow_edges(s);
    }
    // The baked multiple scattering: the direction's part of the volume's source once per ray.
    const LightVolume* volume = light_.multiple_scattering == MultipleScattering::baked && light_.light_volume &&
            !light_.light_volume->empty() && fog_.medium
        ? light_.light_volume.get()
        : nullptr;
    double weights_m[light_volume_max_bands * light_volume_max_bands] = {},
                                              weights_h[light_volume_max_bands * light_volume_max_bands] = {};
    if (volume) {
        volume->phase_weights(-w, g_m, weights_m);
        volume->phase_weights(-w, g_h, weights_h);
    }
    std::size_t k = 0;
    double tau = 0.0;
    for (const MarchStep& st : s.steps) {
        double visible = 1.0, tau_sun = 0.0;
        if (sun_term && !s.knots.empty()) {
            while (k + 1 < s.knots.size() && s.knots[k + 1].t < st.t)
                ++k;
            const SunKnot& a = s.knots[k];
            const SunKnot& b = k + 1 < s.knots.size() ? s.knots[k + 1] : a;
            if (a.visible && b.visible) {
                const double f = b.t > a.t ? std::clamp((st.t - a.t) / (b.t - a.t), 0.0, 1.0) : 0.0;
                tau_sun = a.tau + (b.tau - a.tau) * f;
            } else if (a.visible != b.visible) {  // between the two knots of an edge (steps end there)
                visible = a.visible ? 1.0 : 0.0;
                tau_sun = a.visible ? a.tau : b.tau;
            } else {
                visible = 0.0;
            }
        }
        const auto phase = [&](double g, double albedo) {
            return sun_scattering(light_.multiple_scattering, light_.scattering_octaves, cos_sun, g, albedo, tau_sun,
                                  sun_.z, light_.fit);
        };
        const double sun_m = st.sigma_medium > 0.0 && visible > 0.0 ? phase(g_m, albedo_m) : 0.0;
        const double sun_h = st.sigma_height > 0.0 && visible > 0.0 ? phase(g_h, albedo_h) : 0.0;
        // J of fog_lighting.hpp (pi sun: the sun's irradiance) per medium, times its extinction.
        const glm::dvec3 sun = std::numbers::pi * visible * light_.sun_radiance;
        glm::dvec3 source = albedo_m * st.sigma_medium * (sun * sun_m + light_.ambient) +
            albedo_h * st.sigma_height * (sun * sun_h + light_.ambient);
        if (volume) {  // inside the shell; in the terrain's shadow too, at its part's light (in_scattered_at)
            const glm::dvec3 p = o + w * st.t;
            const MediumColumn column = fog_.medium->column(p.x, p.y);
            const double h = shell_height(volume->shell(column, p.x, p.y), p.z), scale = volume->column_scale(column);
            if (h >= 0.0)
                source += light_.sun_radiance *
                    (albedo_m * st.sigma_medium * volume->in_scattered_at(p.x, p.y, p.z, h, weights_m, scale) +
                     albedo_h * st.sigma_height * volume->in_scattered_at(p.x, p.y, p.z, h, weights_h, scale));
        }
        const double sigma = st.sigma_medium + st.sigma_height;
        // Seen through the air in front of the step: J e^(-beta t) + H (1 - e^(-beta t)).
        if (light_.air.extinction > 0.0) {
            const double haze = light_.air.haze(st.t);
            source = source * (1.0 - haze) + sigma * haze * light_.air.radiance;
        }
        r.inscatter += std::exp(-st.tau_before) * source * step_weight(sigma, st.dt);
        tau = st.tau_before + sigma * st.dt;
    }
    r.transmittance = std::exp(-tau);
    r.steps = int(s.steps.size());
    r.sun_knots = int(s.knots.size());
    if (r.hit_terrain && o_.shade_terrain) {
        // terrain.frag hazes the lit ground as the air above says; a black ground stays black.
        glm::dvec3 shade;
        r.surface = light_.air.seen(surface_radiance(o + w * t_end, s, &shade, &r.ground_sun), t_end);
        r.fog_shade = shade * (1.0 - light_.air.haze(t_end));
    } else if (!r.hit_terrain)
        r.surface = sky_radiance(w);
    return r;
}

}  // namespace kiri::geometry::detail
