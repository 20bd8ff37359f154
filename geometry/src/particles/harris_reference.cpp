#include "kiri/geometry/particles/harris_reference.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "kiri/geometry/particles/particle_footprint.hpp"

namespace kiri::geometry {
namespace {

struct LightSpace {
    glm::dvec3 light, u, v;
    explicit LightSpace(const glm::dvec3& l)
    {
        const double len = glm::length(l);
        if (!(len > 0.0) || !std::isfinite(len))
            throw std::invalid_argument("harris_light_pass: the light direction must be finite and not zero");
        light = l / len;
        const glm::dvec3 side = glm::cross(glm::dvec3(0.0, 0.0, 1.0), light);
        u = glm::length(side) > 1e-9 ? glm::normalize(side) : glm::dvec3(1.0, 0.0, 0.0);
        v = glm::normalize(glm::cross(light, u));
    }
};

// One step of (3)-(4): I_k = g_(k-1) + T_(k-1) I_(k-1), g = a c (1 - T) I, never below e^min_log_gain I.
double step(double intensity, const Particle& occluder, double rho, double forward)
{
    const double t = footprint_transmittance(rho, occluder.radius, occluder.optical_depth);
    const double g = std::clamp(occluder.albedo, 0.0, 1.0) * std::clamp(forward, 0.0, 1.0) * (1.0 - t) * intensity;
    return std::max(g + t * intensity, std::exp(min_log_gain) * intensity);
}

// Sun order: nearest the sun first (largest L.p), ties by index.
std::vector<std::size_t> sun_order(const std::vector<double>& height)
{
    std::vector<std::size_t> order(height.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return height[a] > height[b] || (height[a] == height[b] && a < b); });
    return order;
}

}  // namespace

std::vector<double> harris_light_pass(const ParticleCloud& cloud, const glm::dvec3& light, HarrisStats* stats)
{
    const LightSpace s(light);
    const std::vector<Particle>& P = cloud.particles;
    const std::size_t n = P.size();
    std::vector<double> height(n), pu(n), pv(n);
    double r_max = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
        height[k] = glm::dot(s.light, P[k].position);
        pu[k] = glm::dot(s.u, P[k].position);
        pv[k] = glm::dot(s.v, P[k].position);
        if (std::isfinite(P[k].radius))
            r_max = std::max(r_max, P[k].radius);
    }
    const std::vector<std::size_t> order = sun_order(height);
    std::vector<std::size_t> rank(n);
    for (std::size_t i = 0; i < n; ++i)
        rank[order[i]] = i;
    // Columns of the light plane, cells of the largest radius; each cell lists its particles in
    // sun order, so a receiver reads the occluders before it and stops.
    const double cell = std::max(r_max, 1e-9);
    const auto key = [](long long i, long long j) {
        return (std::uint64_t(i) << 32) ^ std::uint64_t(std::uint32_t(j));
    };
    std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells;
    for (std::size_t i : order)
        cells[key((long long)std::floor(pu[i] / cell), (long long)std::floor(pv[i] / cell))].push_back(i);

    std::vector<double> gamma(n, 1.0);
    std::vector<std::size_t> found;
    HarrisStats counts;
    for (std::size_t k = 0; k < n; ++k) {
        found.clear();
        const long long ci = (long long)std::floor(pu[k] / cell), cj = (long long)std::floor(pv[k] / cell);
        for (long long dj = -1; dj <= 1; ++dj)
            for (long long di = -1; di <= 1; ++di) {
                const auto it = cells.find(key(ci + di, cj + dj));
                if (it == cells.end())
                    continue;
                for (std::size_t j : it->second) {
                    if (rank[j] >= rank[k])
                        break;
                    ++counts.pairs_tested;
                    const double du = pu[j] - pu[k], dv = pv[j] - pv[k];
                    if (du * du + dv * dv < P[j].radius * P[j].radius)
                        found.push_back(j);
                }
            }
        std::sort(found.begin(), found.end(), [&](std::size_t a, std::size_t b) { return rank[a] < rank[b]; });
        double intensity = 1.0;
        for (std::size_t j : found)
            intensity = step(intensity, P[j], std::hypot(pu[j] - pu[k], pv[j] - pv[k]), cloud.forward_scattering);
        counts.occluders += found.size();
        gamma[k] = intensity;
    }
    if (stats)
        *stats = counts;
    return gamma;
}

std::vector<double> harris_light_pass_quadratic(const ParticleCloud& cloud, const glm::dvec3& light)
{
    const LightSpace s(light);
    const std::vector<Particle>& P = cloud.particles;
    const std::size_t n = P.size();
    std::vector<double> height(n), pu(n), pv(n);
    for (std::size_t k = 0; k < n; ++k) {
        height[k] = glm::dot(s.light, P[k].position);
        pu[k] = glm::dot(s.u, P[k].position);
        pv[k] = glm::dot(s.v, P[k].position);
    }
    const std::vector<std::size_t> order = sun_order(height);
    std::vector<double> gamma(n, 1.0);
    for (std::size_t a = 0; a < n; ++a) {
        const std::size_t k = order[a];
        double intensity = 1.0;
        for (std::size_t b = 0; b < a; ++b) {
            const std::size_t j = order[b];
            const double du = pu[j] - pu[k], dv = pv[j] - pv[k];
            if (du * du + dv * dv < P[j].radius * P[j].radius)
                intensity = step(intensity, P[j], std::hypot(du, dv), cloud.forward_scattering);
        }
        gamma[k] = intensity;
    }
    return gamma;
}

}  // namespace kiri::geometry
