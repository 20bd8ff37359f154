#pragma once
// The fog's shade on the ground: tau_sun (sun_volume.glsl: the Medium's marched, the height fog's
// in closed form) at each vertex of the terrain's mesh, the sunlight that reaches the ground
// through the fog (terrain.frag: e^-tau), as the CPU reference lights its ground. One compute
// pass when the sun, the fog or the mesh change; a vertex attribute per frame, nothing more per
// fragment (the height fog's closed form there cost the default scene's terrain pass a third
// more on llvmpipe, for 0.1 % of error from above).
#include <optional>

#include <glm/vec3.hpp>

#include "gl_objects.hpp"
#include "kiri/geometry/volume/height_fog.hpp"
#include "shader_program.hpp"

namespace kiri::render::detail {

class SunVolume;

class GroundShade {
public:
    //! Brings tau_sun per vertex up to date for `vertex_count` vertices of `vertices` (stride
    //! `stride` floats, the position first; `mesh` counts their uploads). Null `sun`, or one
    //! without a Medium or a height fog: none (false). True when there is one to draw with (buffer()).
    bool update(const SunVolume* sun, const glm::vec3& sun_direction, GLuint vertices, int vertex_count, int stride,
                int mesh);
    //! Whether update would run its pass.
    bool stale(const SunVolume* sun, const glm::vec3& sun_direction, int vertex_count, int mesh) const;
    //! One float per vertex: tau_sun; 0 when update returned false.
    GLuint buffer() const { return ready_ ? depths_.get() : 0; }
    int updates() const { return updates_; }

private:
    struct Key {
        int mesh = 0;
        int vertex_count = 0;
        glm::vec3 sun{0.0f};
        const void* medium = nullptr;
        int sun_volume_updates = 0;  // the Medium's grids, options or time changed
        geometry::HeightFog haze;
        bool operator==(const Key&) const = default;
    };
    static std::optional<Key> key(const SunVolume* sun, const glm::vec3& sun_direction, int vertex_count, int mesh);
    std::optional<ShaderProgram> program_;  // built on first use: a scene without fog never pays for it
    Buffer depths_;
    std::optional<Key> built_;
    bool ready_ = false;
    int updates_ = 0;
};

}  // namespace kiri::render::detail
