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
    //! Combined mode: the froxels draw their share of the Medium (fog_partition.glsl), set
    //! with the other uniforms by bind().
    void set_partition(bool partitioned, const glm::vec4& partition)
    {
        partitioned_ = partitioned;
        partition_ = partition;
    }

private:
    Texture grid_, noise_;
    const geometry::Medium* medium_ = nullptr;
    const void* uploaded_ = nullptr;
    bool partitioned_ = false;
    glm::vec4 partition_{0.0f};
};

}  // namespace kiri::render::detail
