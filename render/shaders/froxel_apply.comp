#version 450 core
// Pass 4 over the frame: the fog each pixel of the resolved linear-radiance frame (RGBA16F,
// before the tone map) gets at its depth, radiance T + in-scattered radiance, from u_fog (the
// fog-aware apply's froxel_upsample.comp and froxel_pixels.comp: (in-scattered radiance, T)).
// Where the pixel's samples see different fog (u_split, froxel_edges.comp) its fog is their
// mean from u_split_fog instead (froxel_pixels.comp: each sample's own ray to its own surface,
// as one (S, T) over the resolved colour; S may be negative, the result is not).
layout(local_size_x = 32, local_size_y = 8) in;
layout(rgba16f, binding = 0) uniform image2D io_color;
uniform sampler2D u_fog;
uniform int u_splits;  // u_split and u_split_fog are this frame's
uniform sampler2D u_split;
uniform sampler2D u_split_fog;
uniform ivec2 u_size;

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= u_size.x || px.y >= u_size.y)
        return;
    bool split = u_splits != 0 && texelFetch(u_split, px, 0).r > 0.0;
    vec4 fog = split ? texelFetch(u_split_fog, px, 0) : texelFetch(u_fog, px, 0);
    if (split || !(fog.a >= 1.0 && all(equal(fog.rgb, vec3(0.0))))) {
        vec4 c = imageLoad(io_color, px);
        imageStore(io_color, px, vec4(max(c.rgb * fog.a + fog.rgb, vec3(0.0)), c.a));
    }
}
