#pragma once
// What a billboard's light needs of its particle alone, made once per particle in a compute
// pass (particle_light.comp) instead of in every fragment: the particle's own place in the
// attenuation buffer's grid, the terrain's shadow at its centre, the share of its own column
// that shades it (measured against the Medium's optical depth towards the sun where there is a
// Medium), and the log gain of its own footprint in each light column its billboard can read
// (particle_light.glsl takes the own cylinder out of a fragment's read with four table reads
// instead of four footprint gains). None of it depends on the eye: it is rebuilt when the
// attenuation buffer is (the sun, the particles, the buffer's options), the terrain's shadow map
// or the sun volume changed, never for a still view or a moving eye.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "gl_objects.hpp"
#include "shader_program.hpp"

namespace kiri::geometry {
struct ParticleCloud;
}
namespace kiri::render {
class AttenuationBuffer;
}
namespace kiri::render::detail {

class ShadowMapPass;
class SunVolume;

class ParticleLight {
public:
    ParticleLight();
    //! Brings the per-particle buffers up to date with `buffer` (built), the shadow map (null:
    //! none) and the sun volume (null or without a Medium: each billboard takes the fixed share
    //! geometry::billboard_own_share of its own column); returns whether it rebuilt them.
    bool update(const geometry::ParticleCloud& cloud, const AttenuationBuffer& buffer, const ShadowMapPass* shadow,
                const SunVolume* sun = nullptr);
    //! Binds the records (SSBO 4) and the gain table (SSBO 5) that particle_light.glsl reads.
    void bind() const;
    //! Whether fragments read the table (false: it would pass table_limit floats, and they
    //! compute the four gains themselves, as before).
    bool has_table() const { return table_floats_ > 0; }
    int rebuild_count() const { return rebuilds_; }
    //! log Gamma at points (relative to the buffer's particle centre) on the billboards of the
    //! particles in the buffer's slots: (as a fragment reads it through the record and the
    //! table, with the own cylinder computed in full), read back. After update().
    std::vector<glm::vec2> sample_log_gamma(const geometry::ParticleCloud& cloud, const AttenuationBuffer& buffer,
                                            const std::vector<glm::vec3>& points,
                                            const std::vector<std::uint32_t>& slots) const;
    std::size_t table_floats() const { return table_floats_; }
    std::size_t bytes() const { return records_bytes_ + table_floats_ * sizeof(float); }
    //! Most floats the gain table may hold (256 MiB).
    static constexpr std::size_t table_limit = std::size_t(1) << 26;

private:
    ShaderProgram program_;
    mutable std::unique_ptr<ShaderProgram> sample_;  // built on first use
    Buffer records_, table_;
    std::size_t table_floats_ = 0, records_bytes_ = 0;
    int rebuilds_ = 0;
    // What the buffers were made from.
    int buffer_builds_ = -1, shadow_updates_ = -1, sun_updates_ = -1;
    const ShadowMapPass* shadow_ = nullptr;
    const SunVolume* sun_ = nullptr;
};

}  // namespace kiri::render::detail
