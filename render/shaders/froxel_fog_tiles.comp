#version 450 core
// Lists the tiles whose rays cross fog (froxel_fog_tiles.glsl), counting the groups of the
// indirect dispatch of the passes over their froxels.
layout(local_size_x = 8, local_size_y = 8) in;

void main()
{
    ivec2 tile = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(tile, u_fx_size.xy)))
        return;
    vec2 range = fx_tile_range(tile);
    if (range.y > range.x)
        ft_tiles[atomicAdd(ft_dispatch.x, 1u)] = uint(tile.x) | (uint(tile.y) << 16);
}
