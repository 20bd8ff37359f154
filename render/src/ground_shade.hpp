#pragma once
// The fog's shade on the ground: tau_sun (sun_volume.glsl: the Medium's marched, the height fog's
// in closed form) at each vertex of the terrain's mesh, the sunlight that reaches the ground
// through the fog (terrain.frag: e^-tau), as the CPU reference lights its ground. One compute
// pass when the sun, the fog or the mesh change; a vertex attribute per frame. Where the shade
// bends between a vertex's neighbours (a fog's shore or wall within a cell) the vertex is marked,
// and a fine map (3 samples a cell) is marched in the cells around it, which their fragments read
// (ground_shade.glsl); elsewhere nothing more per fragment (the height fog's closed form
// everywhere cost the default scene's terrain pass a third more on llvmpipe, for 0.1 % of error
// from above).
#include <optional>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "gl_objects.hpp"
#include "kiri/geometry/volume/height_fog.hpp"
#include "shader_program.hpp"

namespace kiri::render::detail {

class SunVolume;

class GroundShade {
public:
    //! The mesh's tensor grid: the DEM's samples (nx by ny, `spacing` apart from `origin`) with
    //! `rings` of the surround before them, `columns` vertices a row.
    struct Grid {
        int nx = 0, ny = 0, columns = 0, rings = 0;
        glm::vec2 origin{0.0f}, spacing{1.0f};
        bool operator==(const Grid&) const = default;
    };
    //! Brings tau_sun per vertex up to date for `vertex_count` vertices of `vertices` (stride
    //! `stride` floats, the position first; `mesh` counts their uploads) on `grid`, and the fine
    //! map where it bends. Null `sun`, or one without a Medium or a height fog: none (false). True
    //! when there is one to draw with (buffer()).
    bool update(const SunVolume* sun, const glm::vec3& sun_direction, GLuint vertices, int vertex_count, int stride,
                const Grid& grid, int mesh);
    //! Whether update would run its pass.
    bool stale(const SunVolume* sun, const glm::vec3& sun_direction, int vertex_count, int mesh) const;
    //! Two floats per vertex: tau_sun, and 1 where the fragments around the vertex read the fine
    //! map instead of interpolating it (else 0); 0 when update returned false.
    GLuint buffer() const { return ready_ ? depths_.get() : 0; }
    int updates() const { return updates_; }
    //! How many vertices the last update marked to refine (0 when update returned false).
    int refined_vertices() const { return ready_ ? refined_ : 0; }
    //! Sets ground_shade.glsl's uniforms of `program` and binds the fine map to `unit` (only
    //! when refined_vertices() > 0).
    void bind_fine(const ShaderProgram& program, int unit) const;

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
    Buffer marks_;  // phase 1's count of marked vertices, then their grid indices
    Texture fine_;
    glm::ivec2 fine_size_{0};
    int fine_scale_ = 0;
    Grid grid_;
    std::optional<Key> built_;
    bool ready_ = false;
    int updates_ = 0;
    int refined_ = 0;
};

}  // namespace kiri::render::detail
