// Library: the tiles whose rays cross fog (a range of depths, fx_tile_range), as
// froxel_fog_tiles.comp lists them, and the froxel an invocation of a pass over their froxels
// alone takes (froxel_density.comp, froxel_lighting.comp: a group of 64, a tile's slices, 64 at a
// time). Every other froxel holds no fog, and its value is cleared before. On llvmpipe a pass
// over the whole volume ran the light of every froxel whether its lanes had fog or not.
layout(std430, binding = 0) buffer FogTiles {
    uvec4 ft_dispatch;  // groups: x the tiles listed, y their slices / 64, z 1; w unused
    uint ft_tiles[];    // x | y << 16
};

// The froxel this invocation takes; z at or past u_fx_size.z: none.
ivec3 ft_froxel()
{
    uint tile = ft_tiles[gl_WorkGroupID.x];
    return ivec3(int(tile & 0xffffu), int(tile >> 16), int(gl_WorkGroupID.y * 64u + gl_LocalInvocationIndex));
}
