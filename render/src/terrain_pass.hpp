#pragma once
#include <cstddef>
#include <memory>

#include <glm/vec3.hpp>

#include "frame_context.hpp"
#include "ground_shade.hpp"
#include "shader_program.hpp"

namespace kiri::geometry {
class Terrain;
}

namespace kiri::render::detail {

//! The ground (kiri/geometry/terrain/ground.hpp) as one indexed mesh, uploaded once per
//! (terrain, exaggeration, surround): the grid, then the surround's rings around it, spaced a
//! cell at the edge and growing outwards to where the surround reaches its base level (the sky
//! pass draws the flat ground beyond).
class TerrainPass {
public:
    TerrainPass();
    //! Returns true when it had to upload (the terrain, the exaggeration or the surround changed).
    bool set_terrain(const geometry::Terrain& terrain, double exaggeration, bool surround = true);
    bool has_terrain() const { return levels_[0].grid.count > 0; }
    //! The fog the sun shines through onto the ground: the sun volume's Medium and height fog
    //! (GroundShade: tau_sun per vertex, rebuilt when the sun, the fog or the mesh change). Null,
    //! or a volume without either, lights the ground fully. Returns true when it rebuilt.
    bool set_fog_shade(const class SunVolume* sun, const glm::vec3& sun_direction);
    //! Whether set_fog_shade would rebuild.
    bool fog_shade_stale(const class SunVolume* sun, const glm::vec3& sun_direction) const
    {
        return has_terrain() && shade_.stale(sun, sun_direction, int(vertex_count_), uploads_);
    }
    //! The mesh's vertices, and those around which the fog's shade is read from its finer map
    //! (set_fog_shade).
    int vertex_count() const { return int(vertex_count_); }
    int refined_shade_vertices() const { return shaded_ ? shade_.refined_vertices() : 0; }
    //! Draws the ground in the shadows of the sun's shadow map (terrain_shadow.glsl; null: no
    //! shadows) and in the fog's shade (set_fog_shade), into a frame of `samples` (null: one a
    //! pixel), each fragment shaded at the samples it shows (terrain.frag).
    void draw(const FrameContext& frame, const class ShadowMapPass* shadow = nullptr,
              const struct FrameSamples* samples = nullptr) const;
    //! Draws the grid's mesh, without the surround, with whatever program is bound (positions at
    //! attribute 0): depth passes (the sun's shadow map ignores the surround).
    void draw_mesh() const;
    //! Sets ground.glsl's uniforms of `program` (colours by height, the sea), and sky.frag's
    //! ground beyond the surround.
    void set_ground_uniforms(const ShaderProgram& program, const FrameContext& frame) const;
    //! What is uploaded (changes when the terrain or the exaggeration do).
    const void* identity() const { return uploaded_heights_; }
    //! The grid drawn by draw() at every (1 / scale)-th sample, scale a power of two in [1/8, 1]
    //! (rounded down to one; terrain_levels.hpp): Renderer::set_terrain_resolution. The depth
    //! passes (draw_mesh) keep the whole grid.
    void set_resolution(double scale);
    //! The grid's triangles draw() draws at the resolution set.
    GLsizei drawn_triangles() const;
    //! Whether the ground runs on beyond the grid to the horizon (the surround is drawn).
    bool surround() const { return uploaded_surround_; }
    //! The grid's bounds (the surround lies outside them).
    glm::dvec3 bounds_min() const { return min_; }
    glm::dvec3 bounds_max() const { return max_; }

private:
    //! Whether and how the ground is in the fog's shade: not at all, from its vertices, or from
    //! the fine map where they are marked (ground_shade.glsl).
    enum class Shade { none, vertices, fine };
    //! The program for a frame with or without the shadow map and a kind of shade: the plain one
    //! built at once, the others on first use.
    const ShaderProgram& program(bool shadow, Shade shade) const;
    mutable std::unique_ptr<ShaderProgram> programs_[2][3];  // [shadow][shade]
    VertexArray vao_;
    Buffer vertices_, indices_;
    GLsizei vertex_count_ = 0;
    int uploads_ = 0;  // of the vertices: the fog's shade is theirs
    GroundShade shade_;
    bool shaded_ = false;           // attribute 2 reads shade_'s buffer
    GroundShade::Grid shade_grid_;  // the mesh's tensor grid
    glm::dvec3 min_{0.0}, max_{-1.0};
    // ground.glsl's and sky.frag's ground uniforms.
    float colour_z_min_ = 0.0f, colour_z_max_ = 0.0f, sea_level_ = 0.0f, water_tolerance_ = 0.0f, base_z_ = 0.0f;
    bool water_ = false;
    // What is on the GPU now, to skip redundant uploads.
    const void* uploaded_heights_ = nullptr;
    std::size_t uploaded_size_ = 0;
    double uploaded_exaggeration_ = 0.0;
    bool uploaded_surround_ = false;
    // The grid's and the surround's levels in the index buffer: every sample, every 2nd, 4th
    // and 8th (terrain_levels.hpp).
    struct Range {
        GLsizei offset = 0, count = 0;
    };
    struct Level {
        Range grid, surround;
    };
    Level levels_[4];
    int level_ = 0;
};

}  // namespace kiri::render::detail
