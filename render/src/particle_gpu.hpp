#pragma once
// Internal: the particles as the GPU passes read them (std430 layouts shared by
// attenuation_buffer.cpp, particles_pass.cpp and the shaders) and the grid's uniforms.
#include <cstdint>
#include <vector>

#include "kiri/geometry/light_grid.hpp"
#include "kiri/geometry/particles.hpp"
#include "shader_program.hpp"

namespace kiri::render::detail {

//! particle_footprint.glsl / attenuation_*.comp: a particle in grid units.
struct GridParticle {
    float grid[4];    // gx, gy, gz (centre), gw0 (shadow-start depth before the shear)
    float optics[4];  // radius (m), tau, albedo, 0
};
static_assert(sizeof(GridParticle) == 32);

//! particles.vert: a particle in the world.
struct WorldParticle {
    float position_radius[4];
    float optics[4];  // tau, albedo, 0, 0
};
static_assert(sizeof(WorldParticle) == 32);

std::vector<GridParticle> grid_particles(const geometry::ParticleCloud& cloud, const geometry::LightGrid& grid);
//! The same particles in 64 buckets of radius (counting sort, O(N)): neighbours in the deposit's
//! SIMD batches then loop over footprints of about the same size.
std::vector<GridParticle> sort_by_footprint(const std::vector<GridParticle>& particles);
std::vector<WorldParticle> world_particles(const geometry::ParticleCloud& cloud);
//! A 64-bit hash of every particle's data and the cloud's constants: equal clouds, equal hash.
std::uint64_t hash_particles(const geometry::ParticleCloud& cloud);
//! u_grid_size, u_grid_voxel, u_grid_shear_cells, u_forward of particle_footprint.glsl.
void set_grid_uniforms(const ShaderProgram& program, const geometry::LightGrid& grid, double forward);

}  // namespace kiri::render::detail
