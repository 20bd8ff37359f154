// Library: the pixels of the frame the froxels' apply fogs (froxel_pixels.comp,
// froxel_upsample.comp): a pixel's screen point and the view depth of its surface.
uniform sampler2D u_depth;   // the frame's window depth (1: the sky)
uniform ivec2 u_size;        // its pixels
uniform float u_near_plane;  // of the frame's projection
uniform float u_far_plane;

vec2 frame_uv(ivec2 px) { return (vec2(px) + 0.5) / vec2(u_size); }

// The view depth of window depth d; 3e38 for the sky.
float frame_view_depth(float d) { return view_depth_or_sky(d, u_near_plane, u_far_plane); }

// The view depth of pixel px's surface; 3e38 for the sky.
float frame_depth(ivec2 px) { return frame_view_depth(texelFetch(u_depth, px, 0).r); }

// The fog-aware apply's grids of samples: at `spacing` (1: every pixel, 2, 4, 8), point c is pixel
// c spacing, or the last pixel of the frame's row or column where that is past it, so that every
// point of a grid either is a point of the next coarser one (twice the spacing) or lies midway
// between two of its points on each axis (the last one excepted where the coarser grid's last
// point is clamped).
uniform int u_spacing;  // the grid this pass works on
ivec2 frame_grid(int spacing) { return spacing == 1 ? u_size : (max(u_size, ivec2(2)) - 2) / spacing + 2; }
ivec2 frame_grid_pixel(ivec2 c, int spacing) { return min(c * spacing, u_size - 1); }
// Per axis, whether point c of the grid at `spacing` is a point of the next coarser one.
bvec2 frame_on_coarser(ivec2 c, int spacing)
{
    ivec2 px = frame_grid_pixel(c, spacing);
    return bvec2((c.x & 1) == 0 || px.x == u_size.x - 1, (c.y & 1) == 0 || px.y == u_size.y - 1);
}

// The list the apply's passes share (froxel_pixels.comp, froxel_upsample.comp): the indirect
// dispatch of the points left to march (groups of 64), the counts, the points of the grid at
// u_spacing (x | y << 16).
layout(std430, binding = 0) buffer FrameMarches {
    uvec4 fm_dispatch;   // groups x, y, z; unused
    uint fm_listed;      // points in fm_pixels
    uint fm_sampled;     // the coarsest grid's points that marched their own rays
    uint fm_upsampled;   // points that took their fog from the coarser grid's around them
    uint fm_unused;
    uint fm_pixels[];
};

// Lists `entry` for a march whose groups of 64 invocations take `per_group` entries each,
// counting the indirect dispatch's groups as the list grows.
void fm_list(uint entry, uint per_group)
{
    uint i = atomicAdd(fm_listed, 1u);
    if (i % per_group == 0u)
        atomicAdd(fm_dispatch.x, 1u);
    fm_pixels[i] = entry;
}
