#pragma once
// The Medium and the height fog on the GPU for froxel_medium.glsl: the grids as one RGBA32F
// texture (floor, bottom, top, coverage), the shared noise tile in float, and the uniforms.
#include "kiri/geometry/height_fog.hpp"
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

private:
    Texture grid_, noise_;
    const geometry::Medium* medium_ = nullptr;
    const void* uploaded_ = nullptr;
};

}  // namespace kiri::render::detail
