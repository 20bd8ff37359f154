#pragma once
// The Medium and the height fog on the GPU for froxel_medium.glsl: the grids as one RGBA32F
// texture (floor, bottom, top, coverage), the shared noise tile in float, and the uniforms.
#include "kiri/geometry/volume/height_fog.hpp"
#include "shader_program.hpp"

namespace kiri::geometry {
class Medium;
}

namespace kiri::render::detail {

class FroxelMedium {
public:
    FroxelMedium();
    //! Uploads the grids when the medium is new (by address and grid data); true when it did.
    bool set(const geometry::Medium* medium);
    //! Sets froxel_medium.glsl's uniforms (the medium's current time and options) and binds the
    //! textures to units grid_unit and grid_unit + 1.
    void bind(const ShaderProgram& program, const geometry::HeightFog& haze, int grid_unit) const;
    //! Sets medium_shell.glsl's uniforms (the grid and the ceiling) and binds the grid to
    //! grid_unit; false (nothing set) without a Medium.
    bool bind_grid(const ShaderProgram& program, int grid_unit) const;
    //! Sets froxel_medium.glsl's height fog uniforms.
    static void bind_height_fog(const ShaderProgram& program, const geometry::HeightFog& haze);
    const geometry::Medium* medium() const { return uploaded_ ? medium_ : nullptr; }
    //! Combined mode: the froxels draw their share of the Medium (fog_partition.glsl), set
    //! with the other uniforms by bind().
    void set_partition(bool partitioned, const glm::vec4& partition, const glm::vec2& depth)
    {
        partitioned_ = partitioned;
        partition_ = partition;
        partition_depth_ = depth;
    }

private:
    Texture grid_, noise_;
    const geometry::Medium* medium_ = nullptr;
    const void* uploaded_ = nullptr;
    bool partitioned_ = false;
    glm::vec4 partition_{0.0f};
    glm::vec2 partition_depth_{0.0f};
};

}  // namespace kiri::render::detail
