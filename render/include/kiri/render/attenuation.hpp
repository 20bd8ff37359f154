#pragma once
//! \file attenuation.hpp
//! Lighting of particle clouds on the GPU ([Shimada08]): the 3D attenuation buffer
//! and, as the speed anchor it is measured against, Harris's light pass as he ran it (one
//! read-back per particle). docs/particles.md describes both.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "kiri/geometry/particles/light_grid.hpp"
#include "kiri/geometry/particles/particles.hpp"

namespace kiri::render {

struct AttenuationOptions {
    int resolution = 128;    //!< voxels per side, 16..1024 (Shimada: 128^3, 256^3, 384^3)
    bool half_float = true;  //!< R16F, else R32F storage of log Gamma
    geometry::LightFrame frame = geometry::LightFrame::automatic;
    int depth_resolution = 0;  //!< slices along the light when > 0 (else `resolution`)
    bool operator==(const AttenuationOptions&) const = default;
};

//! Where a build's time goes: CPU setup (grid, particles in grid units, upload) and the GPU's
//! three steps (GL timestamps).
struct AttenuationBuildTimes {
    double setup_ms = 0.0, deposit_ms = 0.0, scan_ms = 0.0, upload_ms = 0.0;
};

//! The 3D attenuation buffer: a voxel grid along the light (geometry::LightGrid) holding
//! log Gamma = sum of log G_i of the particles up-sun, in a 3D texture read with trilinear
//! filtering. Built by two compute passes, a fixed-point deposit of every particle's footprint
//! into the first voxel of its shadow cylinder (integer atomics: exact, order independent) and a
//! prefix sum down the columns, then copied into the texture on the GPU; no sorting and no
//! read-back. Rebuilt only when the light, the
//! particles or the options change. A GL 4.5 context must be current.
class AttenuationBuffer {
public:
    AttenuationBuffer();
    ~AttenuationBuffer();
    AttenuationBuffer(const AttenuationBuffer&) = delete;
    AttenuationBuffer& operator=(const AttenuationBuffer&) = delete;

    //! The cloud (kept by reference: it must outlive the buffer's use of it). Its contents are
    //! hashed: setting equal particles again does not count as a change.
    void set_particles(const geometry::ParticleCloud& cloud);
    void clear();
    bool has_particles() const;
    //! Rebuilds if the light (towards the sun), the particles or the options changed since the
    //! last build; returns whether it did. Waits for the GPU when it rebuilds.
    bool update(const glm::dvec3& light, const AttenuationOptions& options);
    //! Builds now, whatever changed (benchmarks).
    void rebuild(const glm::dvec3& light, const AttenuationOptions& options);

    int rebuild_count() const;     //!< builds since construction
    double last_build_ms() const;  //!< wall time of the last build (CPU setup + GPU, finished)
    const AttenuationBuildTimes& last_build_times() const;
    const geometry::LightGrid& grid() const;
    std::size_t texture_bytes() const;  //!< the log Gamma texture
    std::size_t scratch_bytes() const;  //!< the fixed-point sums and the scanned floats (8 bytes a voxel)
    double fixed_point_scale() const;   //!< units per 1.0 of log G in the accumulator
    //! Whether the last build packed two columns to a 32-bit word (16-bit magnitudes, half the
    //! atomics), chosen when its scale still resolves log G to 1.2e-4.
    bool packed_deposit() const;
    unsigned texture() const;  //!< GL name of the 3D texture (GL_LINEAR, clamp to edge)
    //! The particles on the GPU: an SSBO of (x, y, z relative to particle_centre(), radius,
    //! tau, albedo, 0, 0) floats per particle, sorted by radius; particle_order()[k] is the
    //! cloud index of entry k. Uploaded when the particles change, not per build.
    unsigned particle_buffer() const;
    const glm::dvec3& particle_centre() const;
    const std::vector<std::uint32_t>& particle_order() const;

    //! Gamma at every particle's centre as the billboards read it (trilinear, minus the
    //! particle's own cylinder), computed on the GPU and read back.
    std::vector<float> gamma_at_particles() const;
    //! The texture read back, voxel (i, j, k) at (k ny + j) nx + i.
    std::vector<float> read_log_gamma() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

struct HarrisGlStats {
    double seconds = 0.0;  //!< sort + the light pass, finished
    int buffer_size = 0;   //!< side of the light buffer (pixels)
    double pixel_m = 0.0;  //!< metres per light-buffer pixel
};

//! Harris & Lastra's light pass on the GPU as [Shimada08] (1)-(4) and [SkyWorks] describe it:
//! particles sorted towards the sun; an orthographic light buffer perpendicular to the light,
//! cleared to 1; for each particle, its light I_k read back from the buffer at its centre, then
//! its footprint multiplied into the buffer (G(rho) per pixel, blending dst * src). Returns
//! Gamma_k = I_k. One read-back per particle: the cost Shimada removes. `buffer_size` 0 picks
//! pixels of a quarter of the smallest radius, at most 2048 a side. A context must be current.
std::vector<float> harris_light_pass_gl(const geometry::ParticleCloud& cloud, const glm::dvec3& light,
                                        int buffer_size = 0, HarrisGlStats* stats = nullptr);

}  // namespace kiri::render
