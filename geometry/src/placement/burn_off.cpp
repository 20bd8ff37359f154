#include "kiri/geometry/placement/burn_off.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <glm/geometric.hpp>

#include "kiri/geometry/core/error.hpp"

namespace kiri::geometry {
namespace {

constexpr double kDeg = M_PI / 180.0;

void check(bool ok, const std::string& label, const char* key, const std::string& why)
{
    if (!ok)
        throw InputError(label, std::string("burn_off/") + key, why);
}

// Upward unit normals of the grid by central differences (one-sided at the border).
std::vector<glm::dvec3> normals(const Heightfield& hf)
{
    std::vector<glm::dvec3> n(hf.size());
    for (int j = 0; j < hf.ny; ++j)
        for (int i = 0; i < hf.nx; ++i) {
            const int i0 = std::max(0, i - 1), i1 = std::min(hf.nx - 1, i + 1);
            const int j0 = std::max(0, j - 1), j1 = std::min(hf.ny - 1, j + 1);
            const double gx = i1 > i0 ? (hf.at(i1, j) - hf.at(i0, j)) / ((i1 - i0) * hf.dx) : 0.0;
            const double gy = j1 > j0 ? (hf.at(i, j1) - hf.at(i, j0)) / ((j1 - j0) * hf.dy) : 0.0;
            n[std::size_t(j) * hf.nx + i] = glm::normalize(glm::dvec3(-gx, -gy, 1.0));
        }
    return n;
}

}  // namespace

glm::dvec3 sun_direction(double latitude_deg, int day_of_year, double solar_hour)
{
    const double phi = latitude_deg * kDeg;
    const double delta = 23.44 * kDeg * std::sin(2.0 * M_PI * (284.0 + day_of_year) / 365.0);
    const double h = 15.0 * kDeg * (solar_hour - 12.0);
    return {-std::cos(delta) * std::sin(h),
            std::sin(delta) * std::cos(phi) - std::cos(delta) * std::cos(h) * std::sin(phi),
            std::sin(delta) * std::sin(phi) + std::cos(delta) * std::cos(h) * std::cos(phi)};
}

FogColumns burn_off(const Heightfield& hf, const FogColumns& dawn, const BurnOffOptions& o, BurnOffReport* report,
                    const std::string& label)
{
    check(o.time >= 0.0 && o.time <= 24.0, label, "time", "must be a solar hour in [0, 24]");
    check(o.day_of_year >= 1 && o.day_of_year <= 366, label, "day_of_year", "must be in [1, 366]");
    check(o.latitude >= -90.0 && o.latitude <= 90.0, label, "latitude", "must be in [-90, 90] degrees");
    check(o.burn_rate >= 0.0 && std::isfinite(o.burn_rate), label, "burn_rate", "must be a finite number >= 0 (m/h)");
    check(o.lift_rate >= 0.0 && std::isfinite(o.lift_rate), label, "lift_rate", "must be a finite number >= 0 (m/h)");
    check(o.extinction > 0.0 && std::isfinite(o.extinction), label, "extinction", "must be > 0 (1/m)");
    check(o.anisotropy >= 0.0 && o.anisotropy < 1.0, label, "anisotropy", "must be in [0, 1)");
    check(o.min_thickness >= 0.0 && std::isfinite(o.min_thickness), label, "min_thickness", "must be >= 0 (m)");
    check(o.step_minutes > 0.0 && o.step_minutes <= 120.0, label, "step_minutes", "must be in (0, 120]");
    if (dawn.nx != hf.nx || dawn.ny != hf.ny || dawn.mask.size() != hf.size())
        throw InputError(label, "burn_off", "the fog columns are not on the terrain's grid");

    // The sun's course from midnight to `time`, in fixed steps (the last one partial), so a
    // later time repeats an earlier one's steps and adds to them: thickness is monotone.
    const double dt = o.step_minutes / 60.0;
    std::vector<glm::dvec3> sun;
    std::vector<double> step;
    for (double t = 0.0; t < o.time - 1e-12; t += dt) {
        const double h = std::min(dt, o.time - t);
        // The full step's midpoint even for the last, partial step: its integrand is then the
        // same at every later time, which makes the result monotone in time.
        sun.push_back(sun_direction(o.latitude, o.day_of_year, t + 0.5 * dt));
        step.push_back(h);
    }
    BurnOffReport rep;
    rep.sunrise_hour = 24.0;
    for (std::size_t s = 0; s < sun.size(); ++s) {
        if (sun[s].z > 0.0 && rep.sunrise_hour == 24.0)
            rep.sunrise_hour = double(s) * dt;
        rep.sun_hours_level += std::max(0.0, sun[s].z) * step[s];
    }
    rep.sun_elevation_deg = std::asin(std::clamp(sun_direction(o.latitude, o.day_of_year, o.time).z, -1.0, 1.0)) / kDeg;

    double lowest = 0.0;
    bool any = false;
    for (std::size_t k = 0; k < dawn.mask.size(); ++k)
        if (dawn.mask[k]) {
            lowest = any ? std::min(lowest, dawn.bottom[k]) : dawn.bottom[k];
            any = true;
        }
    rep.lifted_base = lowest + o.lift_rate * rep.sun_hours_level;

    const std::vector<glm::dvec3> n = normals(hf);
    const double k_tr = 0.75 * (1.0 - o.anisotropy) * o.extinction;
    FogColumns out = dawn;
    const double cell = hf.dx * hf.dy;
    for (std::size_t k = 0; k < dawn.mask.size(); ++k) {
        if (!dawn.mask[k])
            continue;
        rep.cells_before += 1;
        rep.volume_before_m3 += (dawn.top[k] - dawn.bottom[k]) * cell;
        double burnt = 0.0, lifted = lowest;
        const double top = dawn.top[k], bottom0 = dawn.bottom[k];
        for (std::size_t s = 0; s < sun.size() && top - std::max(bottom0 + burnt, lifted) > 0.0; ++s) {
            const double h = top - std::max(bottom0 + burnt, lifted);
            burnt += o.burn_rate * std::max(0.0, glm::dot(n[k], sun[s])) / (1.0 + k_tr * h) * step[s];
            lifted += o.lift_rate * std::max(0.0, sun[s].z) * step[s];
        }
        const double bottom = std::min(top, std::max(bottom0 + burnt, lifted));
        if (top - bottom <= o.min_thickness) {
            out.mask[k] = 0;
            out.top[k] = out.bottom[k] = hf.z[k];
            continue;
        }
        out.bottom[k] = bottom;
        rep.cells_after += 1;
        rep.volume_after_m3 += (top - bottom) * cell;
    }
    if (report)
        *report = rep;
    return out;
}

}  // namespace kiri::geometry
