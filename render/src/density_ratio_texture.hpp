#pragma once
// The particles' density ratio (kiri/geometry/particles/density_ratio.hpp) on the GPU: the balls'
// summed density in a 3D texture over (x, y) relative to the cloud's centre and the shell's height,
// read by particles.frag's density_ratio with the Medium's own extinction.
#include <cstdint>

#include <glm/vec3.hpp>

#include "gl_objects.hpp"
#include "kiri/geometry/particles/density_ratio.hpp"
#include "shader_program.hpp"

namespace kiri::geometry {
class Medium;
struct ParticleCloud;
}  // namespace kiri::geometry

namespace kiri::render::detail {

class DensityRatioTexture {
public:
    //! Builds the grid for the cloud standing for the Medium when either changed (the cloud's
    //! hash, which also covers its centre, or the Medium's address: the pipeline's products are
    //! immutable, a new Medium is a new object), and uploads it relative to `centre`. A null
    //! Medium or a cloud with optics of its own clears it.
    void update(const geometry::ParticleCloud& cloud, std::uint64_t cloud_hash, const geometry::Medium* medium,
                const glm::dvec3& centre);
    bool ready() const { return ready_; }
    //! particles.frag's u_ratio_* uniforms (its KIRI_DENSITY_RATIO variant); the texture, when
    //! ready, on `unit`.
    void bind(const ShaderProgram& program, int unit) const;

private:
    Texture ratio_;
    glm::vec4 xy_{0.0f};  // x0, y0 relative to the centre; 1 / (nx dx), 1 / (ny dy)
    float max_ratio_ = 16.0f;
    std::uint64_t hash_ = 0;
    const geometry::Medium* medium_ = nullptr;
    bool ready_ = false, built_ = false;
};

}  // namespace kiri::render::detail
