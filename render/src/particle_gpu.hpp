#pragma once
// Internal: the particles as the GPU passes read them (one std430 buffer shared by
// attenuation_buffer.cpp, particles_pass.cpp and the shaders) and the grid's uniforms.
#include <cstdint>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "kiri/geometry/particles/light_grid.hpp"
#include "kiri/geometry/particles/particles.hpp"
#include "shader_program.hpp"

namespace kiri::render::detail {

//! A particle on the GPU (particle_footprint.glsl's GpuParticle). Positions are relative to the
//! cloud's centre (float keeps millimetres over 100 km).
struct GpuParticle {
    float position_radius[4];  // x, y, z - centre, radius (m)
    float optics[4];           // tau (opaque: 1e30), albedo, seen_gain (the billboard's and the light's gain on tau), 0
    float floor_plane[4];      // the floor's plane's z - centre (or -no_plane) and dz/dx, dz/dy; 0
    float top_plane[4];        // the top's plane's z - centre (or no_plane) and dz/dx, dz/dy; 0
};
//! The GPU's "no plane" (particles.frag takes a floor below -1e29 and a top above 1e29 as none).
constexpr float no_plane = 1e30f;
static_assert(sizeof(GpuParticle) == 64);

//! The particles sorted into 64 buckets of radius (counting sort, O(N)): the lanes of the
//! deposit's SIMD batches then loop over footprints of about the same size.
struct GpuParticles {
    glm::dvec3 centre{0.0};
    std::vector<GpuParticle> particles;   //!< in the sorted order
    std::vector<std::uint32_t> index;     //!< cloud index of each
    double strongest_log_gain_sum = 0.0;  //!< sum of min(tau seen_gain, 16): bounds every column's |sum of log G|
};
GpuParticles gpu_particles(const geometry::ParticleCloud& cloud);
//! What a billboard and the light's columns multiply tau by: geometry::mass_gain(above_ground),
//! so the part of the particle in the ground or beyond a plane adds to the part that is drawn.
double seen_gain(const geometry::Particle& p);
//! The fixed-point scale (units per 1.0 of |log G|) of the packed deposit, two columns to a
//! 32-bit word: the largest for which no voxel's sum of rounded magnitudes can pass 65535 (per
//! slice, the particles whose shadow can start there, each adding at most min(tau seen_gain, 16) and half a
//! unit of rounding). 0 when none works.
double packed_fixed_point_scale(const geometry::ParticleCloud& cloud, const geometry::LightGrid& grid);
//! A 64-bit hash of every particle's data and the cloud's constants: equal clouds, equal hash.
std::uint64_t hash_particles(const geometry::ParticleCloud& cloud);
//! World (relative to `centre`) -> grid coordinates in voxels, in double.
glm::dmat4 relative_to_grid(const geometry::LightGrid& grid, const glm::dvec3& centre);
//! u_grid_size, u_grid_voxel, u_grid_shear_cells, u_forward, u_to_grid and the grid's axes of
//! particle_footprint.glsl.
void set_grid_uniforms(const ShaderProgram& program, const geometry::LightGrid& grid, double forward,
                       const glm::dvec3& centre);

}  // namespace kiri::render::detail
