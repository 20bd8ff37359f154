#pragma once
// The baked light-transport volume (kiri/geometry/medium/light_volume.hpp) on the GPU, for the
// lighting model's `baked` multiple scattering in the renderers (light_volume.glsl): its moments
// in a 3D texture of RGBA32F, slice q nz + k holding moments 4q .. 4q + 3 of level k (and, after
// them, the cells' sunlit and shadowed parts' L_00), and the cells' floors under a height fog and
// the terrain's shadow's tops in a 2D texture, uploaded when the volume changes. Without a volume the lookups give 0 (single scattering).
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "froxel_medium.hpp"
#include "gl_objects.hpp"
#include "kiri/geometry/medium/light_volume.hpp"
#include "shader_program.hpp"

namespace kiri::render::detail {

//! The preamble of a program that reads the baked light (light_volume.glsl's
//! lv_in_scattered_at), for a frame with it (`baked`) or without: without, the lookup is compiled
//! out (LIGHT_VOLUME 0). llvmpipe runs a branch's code whether any lane takes it or not, and the
//! lookup behind `u_lv_on` ran in every fragment of the layers (their pass 830 -> 720 ms without it).
inline std::string_view light_volume_preamble(bool baked) { return baked ? "" : "#define LIGHT_VOLUME 0\n"; }

class LightVolumeTexture {
public:
    //! The volume to read (kept; null or empty: none) and the Medium it was baked for, whose
    //! columns its cells follow (kept by pointer; null: none). Uploads only what changed.
    void set(std::shared_ptr<const geometry::LightVolume> volume, const geometry::Medium* medium);
    //! The moments are there (the lookups at a point also need the Medium's grid: bind).
    bool ready() const { return volume_ != nullptr && texture_; }
    const geometry::LightVolume* volume() const { return volume_.get(); }
    //! How many volumes were uploaded: what was read from the last one is stale once it moves.
    int updates() const { return updates_; }
    //! Sets light_volume.glsl's uniforms on a program and binds the moments to `unit`, and
    //! medium_shell.glsl's (the Medium's grid) to `unit + 1` when `with_grid` (a program that
    //! has the Medium's grid bound already, the froxels', says false), the cells' floors
    //! (LightVolume::floors) to `unit + 2`; u_lv_on 0 without a
    //! volume, without the grid asked for, or when not `on`. The samplers get their units either way: samplers of different
    //! types may not share one, used or not.
    void bind(const ShaderProgram& program, int unit, bool on = true, bool with_grid = true) const;
    //! lv_in_scattered at the given (x, y, h), column scale, direction towards the eye and g, as
    //! the renderers take it, read back (tests against LightVolume::in_scattered); with `parts`,
    //! scaled to the part on height z's side of the terrain's shadow (LightVolume::in_scattered_at).
    struct Probe {
        glm::vec3 xyh{0.0f};
        float scale = 1.0f;
        glm::vec3 towards{0.0f, 0.0f, 1.0f};
        float g = 0.0f;
        float z = 0.0f;
        float parts = 0.0f;  // 1: take the point's part
        float unused[2] = {0.0f, 0.0f};
    };
    static_assert(sizeof(Probe) == 48, "light_volume_probe.comp reads three vec4 a point");
    std::vector<float> probe(const std::vector<Probe>& points) const;

private:
    std::shared_ptr<const geometry::LightVolume> volume_;
    Texture texture_;
    Texture floors_;      // RG32F: the floors and the terrain's shadow's tops; none without either
    bool parts_ = false;  // the cells' sunlit and shadowed parts (LightVolume::class_means) uploaded
    int groups_ = 0;      // the moments texture's groups of nz slices
    FroxelMedium grid_;
    int updates_ = 0;
    mutable std::unique_ptr<ShaderProgram> probe_;
};

}  // namespace kiri::render::detail
