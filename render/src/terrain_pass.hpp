#pragma once
#include <cstddef>
#include <memory>

#include <glm/vec3.hpp>

#include "frame_context.hpp"
#include "shader_program.hpp"

namespace kiri::geometry {
class Terrain;
}

namespace kiri::render::detail {

//! The terrain as one indexed grid mesh, uploaded once per (terrain, exaggeration).
class TerrainPass {
public:
    TerrainPass();
    //! Returns true when it had to upload (the terrain or the exaggeration changed).
    bool set_terrain(const geometry::Terrain& terrain, double exaggeration);
    bool has_terrain() const { return index_count_ > 0; }
    //! Draws the terrain in the shadows of the sun's shadow map (terrain_shadow.glsl; null: no
    //! shadows).
    void draw(const FrameContext& frame, const class ShadowMapPass* shadow = nullptr) const;
    //! Draws the mesh with whatever program is bound (positions at attribute 0): depth passes.
    void draw_mesh() const;
    //! What is uploaded (changes when the terrain or the exaggeration do).
    const void* identity() const { return uploaded_heights_; }
    glm::dvec3 bounds_min() const { return min_; }
    glm::dvec3 bounds_max() const { return max_; }

private:
    ShaderProgram program_;                                  // no shadow map: no shadows
    mutable std::unique_ptr<ShaderProgram> shadow_program_;  // in the shadow map's shadows, built on first use
    VertexArray vao_;
    Buffer vertices_, indices_;
    GLsizei index_count_ = 0;
    glm::dvec3 min_{0.0}, max_{-1.0};
    // What is on the GPU now, to skip redundant uploads.
    const void* uploaded_heights_ = nullptr;
    std::size_t uploaded_size_ = 0;
    double uploaded_exaggeration_ = 0.0;
};

}  // namespace kiri::render::detail
