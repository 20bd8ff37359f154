#pragma once
// The sun volume: the Medium's optical depth towards the sun, tau_sun, per column and level of
// its shell (medium_shell.glsl), built by one compute pass (sun_volume.comp) when the sun, the
// Medium or its time change, and read by every renderer's lighting (sun_volume.glsl): the
// froxels per froxel and the layers per fragment, instead of each marching or guessing it.
#include <memory>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "froxel_medium.hpp"
#include "gl_objects.hpp"
#include "kiri/geometry/medium/medium.hpp"
#include "kiri/geometry/volume/height_fog.hpp"
#include "shader_program.hpp"

namespace kiri::render::detail {

//! The sun's direction as the marches take it: unit, without a component exactly 0 (the exit of
//! the Medium's box would be 0 x inf).
glm::vec3 sun_march_direction(glm::vec3 direction);

//! The volume's resolution and the march that fills it.
struct SunVolumeResolution {
    //! Columns a side: the grid's samples, at most max_columns, and at least min_columns (each
    //! cell divided evenly: tau_sun bends where the sun's path leaves through the Medium's side,
    //! however coarse its grid). Threads of fog in valleys a few hundred metres wide need columns
    //! closer than the 230 m that 128 gave over Jacksboro's fog (docs/medium.md).
    int min_columns = 64, max_columns = 192;
    int levels = 48;  //!< levels a column (medium_shell.glsl: 60 % of them from floor to top)
    int steps = 48;   //!< steps of each level's march towards the sun
    bool operator==(const SunVolumeResolution&) const = default;
};

class SunVolume {
public:
    SunVolume();
    //! The Medium the sun shines through (null: none; kept by pointer) and the height fog.
    void set(const geometry::Medium* medium, const geometry::HeightFog& haze);
    void set_resolution(const SunVolumeResolution& resolution) { resolution_ = resolution; }
    //! Builds the volume unless the sun, the Medium (its grids, options and time), the height
    //! fog and the resolution are those of the last build; true when it built.
    bool update(const glm::vec3& sun_direction);
    //! Whether update would build.
    bool stale(const glm::vec3& sun_direction) const;
    //! Whether a volume is there to read (a Medium with fog, built).
    bool ready() const { return built_.has_value() && volume_; }
    //! Sets sun_volume.glsl's uniforms and those of medium_shell.glsl and froxel_medium.glsl it
    //! reads (the Medium, the height fog) on a program; textures on units unit, unit + 1 (the
    //! grid, the noise) and unit + 2 (the volume). `use_volume` false, or no volume: the Medium's
    //! part is marched in `march_steps` steps instead.
    void bind(const ShaderProgram& program, int unit, int march_steps, bool use_volume = true) const;
    //! medium_shell.glsl's uniforms alone (the Medium's grid on `unit`), for a program that reads
    //! the shell's columns but not the sun volume (the layers' baked light); false without a Medium.
    bool bind_grid(const ShaderProgram& program, int unit) const { return medium_gpu_.bind_grid(program, unit); }
    //! tau_sun at `points` as the renderers' lighting takes it (sun_volume.glsl, the volume
    //! built by update for `sun_direction`, or marched as bind says), read back.
    std::vector<float> probe(const std::vector<glm::vec3>& points, const glm::vec3& sun_direction, int march_steps,
                             bool use_volume = true) const;
    int updates() const { return updates_; }
    glm::ivec3 size() const { return size_; }
    //! The Medium set (null: none, or one without fog) and the height fog.
    const geometry::Medium* medium() const { return medium_gpu_.medium(); }
    const geometry::HeightFog& haze() const { return haze_; }

private:
    struct Key {
        glm::vec3 sun{0.0f};
        const geometry::Medium* medium = nullptr;
        const void* grids = nullptr;
        geometry::MediumOptions options;
        geometry::MediumDetail detail;  // the height fog is not in it: added where it is read
        SunVolumeResolution resolution;
        bool operator==(const Key&) const = default;
    };
    FroxelMedium medium_gpu_;
    geometry::HeightFog haze_;
    ShaderProgram fill_;
    mutable std::unique_ptr<ShaderProgram> probe_;
    Texture volume_;
    glm::ivec3 size_{0};
    SunVolumeResolution resolution_;
    std::optional<Key> key(const glm::vec3& sun_direction) const;
    std::optional<Key> built_;
    int updates_ = 0;
};

}  // namespace kiri::render::detail
