#pragma once
// The sun's view of the terrain: an orthographic depth map over a region (the terrain and the
// fog), low-passed into an exponential shadow map (shaders esm_blur.comp, terrain_shadow.glsl).
// Rebuilt only when the sun, the terrain or the region change. The renderer keeps one map a
// frame, and every pass that lights something by the sun reads it: the terrain, the froxels'
// lighting, the layers and the particles.
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <memory>
#include <vector>

#include "shader_program.hpp"

namespace kiri::render::detail {

class TerrainPass;

//! The texture unit the shadow map is bound to in every program linking terrain_shadow.glsl
//! (no pass uses it for anything else: samplers of different types may not share a unit).
constexpr int shadow_map_unit = 10;
//! The map's depth before its blur, for the same programs (terrain_shadow.glsl's hard test).
constexpr int shadow_depth_unit = 23;

class ShadowMapPass {
public:
    ShadowMapPass();
    //! Brings the map up to date; returns true when it was rebuilt. sharpness is the ESM exponent
    //! per texel of light depth.
    bool update(const TerrainPass& terrain, const glm::vec3& sun_direction, const glm::dvec3& lo, const glm::dvec3& hi,
                int size, double sharpness);
    bool ready() const { return bool(esm_[1]); }
    //! Sets terrain_shadow.glsl's uniforms on `program` and binds the map to shadow_map_unit;
    //! with on = false (or before the first update) the library's visibility is 1 everywhere.
    void bind(const ShaderProgram& program, bool on) const;
    //! Size of a shadow-map texel in metres (the scale of its blur).
    double texel_metres() const { return texel_m_; }
    int updates() const { return updates_; }
    //! The visibility terrain_shadow.glsl gives each point (world metres), read back: for tests.
    std::vector<float> probe(const std::vector<glm::vec3>& points) const;

private:
    ShaderProgram depth_program_, blur_;
    mutable std::unique_ptr<ShaderProgram> probe_;
    Framebuffer fbo_;
    Texture depth_, esm_[2];
    int size_ = 0, updates_ = 0;
    glm::mat4 matrix_{1.0f};                                // world -> [0, 1]^2 and light depth in metres
    float k_ = 0.0f, texel_m_ = 0.0f, depth_range_ = 0.0f;  // depth_range_: the map's depth extent (m)
    // What the map was built from.
    glm::vec3 sun_{0.0f};
    glm::dvec3 lo_{0.0}, hi_{-1.0};
    double sharpness_ = 0.0;
    const void* terrain_ = nullptr;
    // The sun below the horizon of a ground that runs on to it (the surround): every point of
    // the fog is in the ground's shadow, whatever the map, which holds the grid alone, says.
    bool sun_set_ = false;
};

//! terrain_shadow.glsl's uniforms on `program`: map's shadows, or none where map is null.
void bind_terrain_shadow(const ShaderProgram& program, const ShadowMapPass* map);

}  // namespace kiri::render::detail
