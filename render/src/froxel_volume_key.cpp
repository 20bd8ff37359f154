#include "froxel_volume_key.hpp"

namespace kiri::render::detail {

FroxelVolumeKey make_froxel_volume_key(const FrameContext& frame, const void* terrain, const geometry::Medium* medium,
                                       const geometry::FroxelOptions& options)
{
    FroxelVolumeKey k;
    k.view = frame.view;
    k.projection = frame.projection;
    k.width = frame.width;
    k.height = frame.height;
    k.sun_direction = frame.sun_direction;
    k.sun_radiance = frame.sun_radiance;
    k.ambient = frame.ambient;
    k.partitioned = frame.partitioned;
    k.partition = frame.partition;
    k.terrain = terrain;
    k.medium = medium;
    if (medium) {
        k.medium_grids = medium->grid().top.data();
        k.medium_options = medium->options();
        k.medium_detail = medium->detail();
    }
    k.options = options;
    return k;
}

}  // namespace kiri::render::detail
