#include "particle_gpu.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace kiri::render::detail {

std::vector<GridParticle> grid_particles(const geometry::ParticleCloud& cloud, const geometry::LightGrid& g)
{
    std::vector<GridParticle> out(cloud.particles.size());
    for (std::size_t k = 0; k < out.size(); ++k) {
        const geometry::Particle& p = cloud.particles[k];
        const glm::dvec3 q = g.light_coordinates(p.position);
        const glm::dvec3 c = g.to_grid(p.position);
        // Shadow start in column (i, j): gw0 - a' (i + 0.5) - b' (j + 0.5) (LightGrid::shadow_start).
        const double gw0 = (q.z - g.shear_u * g.origin.x - g.shear_v * g.origin.y - g.origin.z) / g.voxel.z;
        const double tau = std::isfinite(p.optical_depth) ? p.optical_depth : 1e30;
        out[k] = {{float(c.x), float(c.y), float(c.z), float(gw0)}, {float(p.radius), float(tau), float(p.albedo), 0.0f}};
    }
    return out;
}

std::vector<GridParticle> sort_by_footprint(const std::vector<GridParticle>& particles)
{
    constexpr int buckets = 64;
    float r_max = 0.0f;
    for (const GridParticle& p : particles)
        r_max = std::max(r_max, std::isfinite(p.optics[0]) ? p.optics[0] : 0.0f);
    const auto bucket = [&](const GridParticle& p) {
        const float x = r_max > 0.0f && std::isfinite(p.optics[0]) ? p.optics[0] / r_max : 0.0f;
        return std::clamp(int(x * buckets), 0, buckets - 1);
    };
    std::vector<std::size_t> start(buckets + 1, 0);
    for (const GridParticle& p : particles)
        ++start[std::size_t(bucket(p)) + 1];
    for (int b = 0; b < buckets; ++b)
        start[std::size_t(b) + 1] += start[std::size_t(b)];
    std::vector<GridParticle> out(particles.size());
    for (const GridParticle& p : particles)
        out[start[std::size_t(bucket(p))]++] = p;
    return out;
}

std::vector<WorldParticle> world_particles(const geometry::ParticleCloud& cloud)
{
    std::vector<WorldParticle> out(cloud.particles.size());
    for (std::size_t k = 0; k < out.size(); ++k) {
        const geometry::Particle& p = cloud.particles[k];
        const double tau = std::isfinite(p.optical_depth) ? p.optical_depth : 1e30;
        out[k] = {{float(p.position.x), float(p.position.y), float(p.position.z), float(p.radius)},
                  {float(tau), float(p.albedo), 0.0f, 0.0f}};
    }
    return out;
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
    }
    return h;
}

void set_grid_uniforms(const ShaderProgram& program, const geometry::LightGrid& g, double forward)
{
    glProgramUniform3i(program.id(), program.location("u_grid_size"), g.size[0], g.size[1], g.size[2]);
    program.set("u_grid_voxel", glm::vec3(g.voxel));
    program.set("u_grid_shear_cells", glm::vec2(float(g.shear_u * g.voxel.x / g.voxel.z), float(g.shear_v * g.voxel.y / g.voxel.z)));
    program.set("u_forward", float(forward));
}

}  // namespace kiri::render::detail
