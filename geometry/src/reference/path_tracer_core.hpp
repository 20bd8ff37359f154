#pragma once
// Internal: the path tracer's pieces (path_tracer.hpp says what it computes), shared with the
// bake of the light-transport volume (light_volume_bake.hpp), which traces the sun's light
// forward through the same media with the same free paths and phase sampling.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "kiri/geometry/reference/path_tracer.hpp"
#include "reference/grid_walk.hpp"
#include "reference/heightfield_ray.hpp"

namespace kiri::geometry::detail {

// splitmix64 (a 64-bit mixer), used to seed the generator from (seed, stream).
inline std::uint64_t splitmix64(std::uint64_t& x)
{
    std::uint64_t z = (x += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

// xoshiro256** [Blackman21]: one independent stream per pixel (or photon).
class Random {
public:
    Random(std::uint64_t seed, std::uint64_t stream)
    {
        std::uint64_t x = seed;
        const std::uint64_t a = splitmix64(x);
        x = stream ^ a;
        for (std::uint64_t& v : s_)
            v = splitmix64(x);
    }
    //! Uniform in [0, 1).
    double uniform() { return double(next() >> 11) * 0x1.0p-53; }

private:
    std::uint64_t s_[4];
    static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
    std::uint64_t next()
    {
        const std::uint64_t result = rotl(s_[1] * 5, 7) * 9, t = s_[1] << 17;
        s_[2] ^= s_[0];
        s_[3] ^= s_[1];
        s_[1] ^= s_[2];
        s_[0] ^= s_[3];
        s_[2] ^= t;
        s_[3] = rotl(s_[3], 45);
        return result;
    }
};

// A unit vector about `axis` (unit) at cos_theta from it and azimuth phi.
inline glm::dvec3 around(const glm::dvec3& axis, double cos_theta, double phi)
{
    const glm::dvec3 helper = std::abs(axis.x) < 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
    const glm::dvec3 t = glm::normalize(glm::cross(helper, axis));
    const glm::dvec3 b = glm::cross(axis, t);
    const double c = std::clamp(cos_theta, -1.0, 1.0), s = std::sqrt(std::max(0.0, 1.0 - c * c));
    return glm::normalize(axis * c + (t * std::cos(phi) + b * std::sin(phi)) * s);
}

// The scattered direction of light travelling along w, drawn from the Henyey-Greenstein phase
// function ([HG41]) by inverting its cumulative distribution in cos_theta, from two uniforms in
// [0, 1): u for cos_theta, v for the azimuth (stratified ones where the caller has them).
inline glm::dvec3 sample_phase(const glm::dvec3& w, double g, double u, double v)
{
    const double phi = 2.0 * std::numbers::pi * v;
    double c = 1.0 - 2.0 * u;
    if (std::abs(g) >= 1e-4) {
        const double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
        c = (1.0 + g * g - s * s) / (2.0 * g);
    }
    return around(w, c, phi);
}

// The same from the generator (u first, then v).
inline glm::dvec3 sample_phase(const glm::dvec3& w, double g, Random& rng)
{
    const double u = rng.uniform();
    return sample_phase(w, g, u, rng.uniform());
}

// The majorant of the Medium over one cell of its grid: sigma_t <= sigma there, and the
// Medium is empty outside z_lo <= z <= z_hi. Between core_lo and core_hi every point of the
// cell is inside the shell and sigma_t >= control there (the control variate of residual ratio
// tracking; 0 where there is no such bound).
struct MajorantCell {
    double sigma = 0.0, z_lo = 0.0, z_hi = 0.0;
    double control = 0.0, core_lo = 0.0, core_hi = 0.0;
};

class PathTracer {
public:
    PathTracer(const FogVolume& fog, const Heightfield* terrain, const FogLighting& light,
               const PathTracerOptions& options);
    glm::dvec3 sample(const glm::dvec3& origin, const glm::dvec3& dir, double t_max, Random& rng,
                      long long& vertices) const;

    //! The distance to the Medium's next real collision along o + t w before t1 (delta
    //! tracking), +inf if none.
    double medium_collision(const glm::dvec3& o, const glm::dvec3& w, double t1, Random& rng) const;
    //! The same for the height fog alone (exactly, by its closed form).
    double haze_collision(const glm::dvec3& o, const glm::dvec3& w, double t1, Random& rng) const;
    //! The sun's transmittance from p (the terrain hides, the fog dims; ratio tracking in the
    //! Medium, an unbiased estimate).
    double sun_transmittance(const glm::dvec3& p, Random& rng) const;
    const HeightFog& haze() const { return haze_; }
    const Medium* medium() const { return medium_; }
    bool has_haze() const { return haze_on_; }
    const HeightfieldRay* terrain() const { return terrain_.get(); }
    double albedo_medium() const { return albedo_medium_; }
    double g_medium() const { return g_medium_; }
    double albedo_haze() const { return albedo_haze_; }
    double g_haze() const { return g_haze_; }

private:
    const Medium* medium_ = nullptr;
    HeightFog haze_;
    bool haze_on_ = false;
    std::unique_ptr<HeightfieldRay> terrain_;
    GridFrame frame_;
    std::vector<MajorantCell> cells_;
    double z_lo_ = 0.0, z_hi_ = 0.0;  // the Medium's bounds in z
    double albedo_medium_ = 0.0, g_medium_ = 0.0, albedo_haze_ = 0.0, g_haze_ = 0.0;
    glm::dvec3 sun_{0.0, 0.0, 1.0}, sun_radiance_{0.0}, ambient_{0.0};
    bool sun_on_ = false, terrain_shadows_ = true, fog_shadows_ = true;
    PathSky sky_ = PathSky::hemisphere;
    bool lambertian_ = true;
    int max_bounces_ = 128, roulette_after_ = 3;

    double medium_transmittance(const glm::dvec3& o, const glm::dvec3& w, Random& rng) const;
    glm::dvec3 sky(const glm::dvec3& w) const;
    //! Calls visit(cell, a, b) for each piece [a, b] of o + t w, t in [t0, t1], inside a cell
    //! that may hold fog, nearest first, until visit returns false.
    template <class Visit>
    void walk_cells(const glm::dvec3& o, const glm::dvec3& w, double t0, double t1, Visit&& visit) const;
};

}  // namespace kiri::geometry::detail
