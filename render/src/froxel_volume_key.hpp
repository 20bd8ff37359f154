#pragma once
// What a froxel volume is computed from. FroxelPass::update reruns the volume's passes when
// a frame's key differs from the last one's; the key holds whole option structs compared by
// value, so an option added to them takes part in the comparison without further code.
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "frame_context.hpp"
#include "kiri/geometry/medium/medium.hpp"
#include "kiri/geometry/volume/froxel_options.hpp"

namespace kiri::render::detail {

struct FroxelVolumeKey {
    // The frame: camera (its depth range too: the far plane is the volume's by default, and
    // the frame's depth bounds the tiles), size, light and the combined mode's share.
    glm::dmat4 view{1.0}, projection{1.0};
    int width = 0, height = 0;
    glm::vec3 sun_direction{0.0f}, sun_radiance{0.0f}, ambient{0.0f};
    bool partitioned = false;
    glm::vec4 partition{0.0f};
    // What the fog is drawn over and from: the terrain's and the medium's identities (the
    // grids' storage: a medium rebuilt in place is a new one, as for FroxelMedium::set), and
    // the options.
    const void* terrain = nullptr;
    const geometry::Medium* medium = nullptr;
    const void* medium_grids = nullptr;
    geometry::MediumOptions medium_options;
    geometry::MediumDetail medium_detail;
    geometry::FroxelOptions options;
    const void* light_volume = nullptr;  // the baked multiple scattering read (LightVolume), if any

    bool operator==(const FroxelVolumeKey&) const = default;
};

//! What the temporal history is laid out by: it stays usable across changes of the view, the
//! sun and the fog (reprojection and the clamp take care of them), not across these.
struct FroxelVolumeLayout {
    int width = 0, height = 0, slices = 0;
    geometry::SliceDistribution distribution = geometry::SliceDistribution::exponential;
    double power = 0.0, log2_scale = 0.0, near = 0.0, far = 0.0;
    bool fog_aware = false;

    bool operator==(const FroxelVolumeLayout&) const = default;
};

inline FroxelVolumeLayout volume_layout(const geometry::FroxelOptions& o)
{
    return {o.width, o.height, o.slices, o.distribution, o.power, o.log2_scale, o.near, o.far, o.fog_aware};
}

//! The key of the volume for this frame; medium may be null (height fog alone).
FroxelVolumeKey make_froxel_volume_key(const FrameContext& frame, const void* terrain, const geometry::Medium* medium,
                                       const geometry::FroxelOptions& options);

}  // namespace kiri::render::detail
