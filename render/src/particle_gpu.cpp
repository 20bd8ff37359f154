#include "particle_gpu.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "kiri/geometry/particles/particle_footprint.hpp"

namespace kiri::render::detail {

double seen_gain(const geometry::Particle& p) { return geometry::mass_gain(p.above_ground); }

GpuParticles gpu_particles(const geometry::ParticleCloud& cloud)
{
    GpuParticles out;
    const auto& P = cloud.particles;
    if (P.empty())
        return out;
    glm::dvec3 lo = P.front().position, hi = lo;
    double r_max = 0.0;
    for (const geometry::Particle& p : P) {
        lo = glm::min(lo, p.position);
        hi = glm::max(hi, p.position);
        if (std::isfinite(p.radius))
            r_max = std::max(r_max, p.radius);
        out.strongest_log_gain_sum +=
            std::min(std::isfinite(p.optical_depth) ? std::max(p.optical_depth, 0.0) * seen_gain(p) : 1e300,
                     -geometry::min_log_gain);
    }
    out.centre = 0.5 * (lo + hi);
    constexpr int buckets = 64;
    const auto bucket = [&](const geometry::Particle& p) {
        const double x = r_max > 0.0 && std::isfinite(p.radius) ? p.radius / r_max : 0.0;
        return std::clamp(int(x * buckets), 0, buckets - 1);
    };
    std::vector<std::size_t> start(buckets + 1, 0);
    for (const geometry::Particle& p : P)
        ++start[std::size_t(bucket(p)) + 1];
    for (int b = 0; b < buckets; ++b)
        start[std::size_t(b) + 1] += start[std::size_t(b)];
    out.particles.resize(P.size());
    out.index.resize(P.size());
    for (std::size_t k = 0; k < P.size(); ++k) {
        const geometry::Particle& p = P[k];
        const std::size_t slot = start[std::size_t(bucket(p))]++;
        const glm::dvec3 q = p.position - out.centre;
        const double tau = std::isfinite(p.optical_depth) ? p.optical_depth : 1e30;
        out.particles[slot] = {{float(q.x), float(q.y), float(q.z), float(p.radius)},
                               {float(tau), float(p.albedo), float(seen_gain(p)), 0.0f},
                               {float(std::isfinite(p.floor) ? p.floor - out.centre.z : -no_plane),
                                float(p.floor_slope.x), float(p.floor_slope.y), 0.0f},
                               {float(std::isfinite(p.top) ? p.top - out.centre.z : no_plane), float(p.top_slope.x),
                                float(p.top_slope.y), 0.0f}};
        out.index[slot] = std::uint32_t(k);
    }
    return out;
}

double packed_fixed_point_scale(const geometry::ParticleCloud& cloud, const geometry::LightGrid& g)
{
    // Bounds per slice and block of 8 x 8 columns: the particles whose shadow can start in that
    // slice inside that block, each at most min(tau seen_gain, 16) and half a unit of rounding
    // per voxel.
    constexpr int block = 8;
    const int nz = g.size[2], bx = (g.size[0] + block - 1) / block, by = (g.size[1] + block - 1) / block;
    std::vector<double> bound(std::size_t(nz) * bx * by, 0.0), count(bound.size(), 0.0);
    const double sa = std::abs(g.shear_u * g.voxel.x / g.voxel.z), sb = std::abs(g.shear_v * g.voxel.y / g.voxel.z);
    for (const geometry::Particle& p : cloud.particles) {
        if (!(p.radius > 0.0) || !(p.optical_depth > 0.0))
            continue;
        const glm::dvec3 q = g.to_grid(p.position);
        // Shadow starts over the footprint: gz + a' (gx - i - 0.5) + b' (gy - j - 0.5), with slack
        // for the GPU's float rounding (~1e-4 of a voxel).
        const double ru = p.radius / g.voxel.x, rv = p.radius / g.voxel.y;
        const double spread = sa * ru + sb * rv + 1e-2;
        const int k0 = int(std::clamp(std::ceil(q.z - spread - 0.5), 0.0, double(nz - 1)));
        const int k1 = int(std::clamp(std::ceil(q.z + spread - 0.5), 0.0, double(nz - 1)));
        const int i0 = int(std::clamp(std::floor((q.x - ru - 1.0) / block), 0.0, double(bx - 1)));
        const int i1 = int(std::clamp(std::floor((q.x + ru + 1.0) / block), 0.0, double(bx - 1)));
        const int j0 = int(std::clamp(std::floor((q.y - rv - 1.0) / block), 0.0, double(by - 1)));
        const int j1 = int(std::clamp(std::floor((q.y + rv + 1.0) / block), 0.0, double(by - 1)));
        const double strongest =
            std::min(std::isfinite(p.optical_depth) ? p.optical_depth * seen_gain(p) : 1e300, -geometry::min_log_gain);
        for (int k = k0; k <= k1; ++k)
            for (int j = j0; j <= j1; ++j)
                for (int i = i0; i <= i1; ++i) {
                    const std::size_t b = (std::size_t(k) * by + j) * bx + i;
                    bound[b] += strongest;
                    count[b] += 1.0;
                }
    }
    double scale = std::numeric_limits<double>::infinity();
    for (std::size_t b = 0; b < bound.size(); ++b)
        if (bound[b] > 0.0)
            scale = std::min(scale, (65535.0 - 0.5 * count[b] - 1.0) / bound[b]);
    if (!std::isfinite(scale) || !(scale > 1.0))
        return 0.0;
    // Down to a step of 2^(1/8): the sums above depend on the particles' order in their last bits,
    // the scale must not (shuffled particles give the same buffer bit for bit).
    return std::exp2(std::floor(8.0 * std::log2(scale) - 1e-6) / 8.0);
}

std::uint64_t hash_particles(const geometry::ParticleCloud& cloud)
{
    // FNV-1a over 64-bit words.
    std::uint64_t h = 1469598103934665603ull;
    const auto mix = [&](double v) {
        std::uint64_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        h = (h ^ bits) * 1099511628211ull;
    };
    mix(double(cloud.particles.size()));
    mix(cloud.forward_scattering);
    mix(cloud.anisotropy);
    for (const geometry::Particle& p : cloud.particles) {
        mix(p.position.x);
        mix(p.position.y);
        mix(p.position.z);
        mix(p.radius);
        mix(p.optical_depth);
        mix(p.albedo);
        mix(p.above_ground);
        mix(p.floor);
        mix(p.floor_slope.x);
        mix(p.floor_slope.y);
        mix(p.top);
        mix(p.top_slope.x);
        mix(p.top_slope.y);
    }
    return h;
}

glm::dmat4 relative_to_grid(const geometry::LightGrid& g, const glm::dvec3& centre)
{
    // to_grid(q + centre) = (world_to_texture (q + centre)) * size.
    glm::dmat4 m = g.world_to_texture();
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 3; ++r)
            m[c][r] *= g.size[r];
    m[3] = m * glm::dvec4(centre, 1.0);
    return m;
}

void set_grid_uniforms(const ShaderProgram& program, const geometry::LightGrid& g, double forward,
                       const glm::dvec3& centre)
{
    glProgramUniform3i(program.id(), program.location("u_grid_size"), g.size[0], g.size[1], g.size[2]);
    program.set("u_grid_voxel", glm::vec3(g.voxel));
    program.set("u_grid_shear_cells",
                glm::vec2(float(g.shear_u * g.voxel.x / g.voxel.z), float(g.shear_v * g.voxel.y / g.voxel.z)));
    program.set("u_forward", float(forward));
    program.set("u_to_grid", glm::mat4(relative_to_grid(g, centre)));
    program.set("u_grid_u_axis", glm::vec3(g.u_axis));
    program.set("u_grid_v_axis", glm::vec3(g.v_axis));
    program.set("u_grid_light", glm::vec3(g.light));
}

}  // namespace kiri::render::detail
