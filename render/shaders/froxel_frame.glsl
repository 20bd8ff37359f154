// Library: the pixels of the frame the froxels' apply fogs (froxel_pixels.comp,
// froxel_upsample.comp): a pixel's screen point and the view depth of its surface.
uniform sampler2D u_depth;   // the frame's window depth (1: the sky)
uniform ivec2 u_size;        // its pixels
uniform float u_near_plane;  // of the frame's projection
uniform float u_far_plane;

vec2 frame_uv(ivec2 px) { return (vec2(px) + 0.5) / vec2(u_size); }

// The view depth of pixel px's surface; 3e38 for the sky.
float frame_depth(ivec2 px)
{
    float d = texelFetch(u_depth, px, 0).r;
    if (d >= 1.0)
        return 3e38;
    float z = d * 2.0 - 1.0;
    return 2.0 * u_near_plane * u_far_plane / (u_far_plane + u_near_plane - z * (u_far_plane - u_near_plane));
}

// The half-resolution samples of the fog-aware apply: sample c is pixel 2c, or the last pixel of
// the frame's row or column where 2c is past it (an even size), so that every pixel either is a
// sample or lies midway between two on each axis.
ivec2 frame_samples() { return u_size / 2 + 1; }
ivec2 frame_sample_pixel(ivec2 c) { return min(2 * c, u_size - 1); }
// Per axis, whether pixel px is in a sample's column (x) or row (y).
bvec2 frame_sampled(ivec2 px) { return bvec2((px.x & 1) == 0 || px.x == u_size.x - 1, (px.y & 1) == 0 || px.y == u_size.y - 1); }

// The list the apply's passes share (froxel_pixels.comp, froxel_upsample.comp): the indirect
// dispatch of the pixels left to march (groups of 64), the counts, the pixels (x | y << 16).
layout(std430, binding = 0) buffer FrameMarches {
    uvec4 fm_dispatch;   // groups x, y, z; unused
    uint fm_listed;      // pixels in fm_pixels
    uint fm_sampled;     // samples that marched their own rays
    uint fm_upsampled;   // pixels that took their fog from the samples around them
    uint fm_unused;
    uint fm_pixels[];
};
