#version 450 core
// The volume's lookup (froxel_fog_at) at the points of the grid at u_spacing that
// froxel_upsample.comp found its slices resolve and listed (FrameMarches, from its second list),
// into o_fog. In a pass of their own: llvmpipe runs a branch's code whether any lane takes it or
// not, and in the upsample's pass the lookup's sixteen texel fetches ran at every point (a third
// of that pass), for the 6 % of the default still's pixels that take it.
layout(local_size_x = 64) in;
layout(rgba32f, binding = 0) writeonly uniform image2D o_fog;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= fm_listed)
        return;
    ivec2 t = ivec2(int(fm_pixels[i] & 0xffffu), int(fm_pixels[i] >> 16));
    ivec2 px = frame_grid_pixel(t, u_spacing);
    imageStore(o_fog, t, froxel_fog_at(frame_uv(px), frame_depth(px)));
}
