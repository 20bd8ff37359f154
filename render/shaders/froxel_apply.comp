#version 450 core
// Pass 4 over the frame: the fog each pixel of the resolved linear-radiance frame (RGBA16F,
// before the tone map) gets at its depth, radiance T + in-scattered radiance, from u_fog (the
// fog-aware apply's froxel_upsample.comp and froxel_pixels.comp: (in-scattered radiance, T)).
// Where the pixel's samples see two surfaces (u_edge: the other side's mean colour B_o and its
// share c of the samples, froxel_edges.comp) each side gets its own fog, the other side's from
// its own march (u_edge_fog): of the resolved colour C = (1 - c) B + c B_o,
// (1 - c) (B T + S) + c (B_o T_o + S_o) = (C - c B_o) T + (1 - c) S + c (B_o T_o + S_o).
// Where they see one surface fogged unevenly, the first side's (T, S) too is its own march
// (u_edge_first_fog), not the centre's: the centre lies between the two.
layout(local_size_x = 32, local_size_y = 8) in;
layout(rgba16f, binding = 0) uniform image2D io_color;
uniform sampler2D u_fog;
uniform int u_edges;  // u_edge and u_edge_fog are this frame's
uniform sampler2D u_edge;
uniform sampler2D u_edge_fog;
uniform sampler2D u_edge_depth;      // g > 0: split by its fog (froxel_edges.comp)
uniform sampler2D u_edge_first_fog;
uniform ivec2 u_size;

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= u_size.x || px.y >= u_size.y)
        return;
    vec4 fog = texelFetch(u_fog, px, 0);
    vec4 edge = u_edges != 0 ? texelFetch(u_edge, px, 0) : vec4(0.0);
    if (edge.a > 0.0) {
        vec4 other = texelFetch(u_edge_fog, px, 0);
        if (texelFetch(u_edge_depth, px, 0).g > 0.0)
            fog = texelFetch(u_edge_first_fog, px, 0);
        vec4 c = imageLoad(io_color, px);
        vec3 rgb = (c.rgb - edge.a * edge.rgb) * fog.a + (1.0 - edge.a) * fog.rgb +
            edge.a * (edge.rgb * other.a + other.rgb);
        imageStore(io_color, px, vec4(max(rgb, vec3(0.0)), c.a));
    } else if (!(fog.a >= 1.0 && all(equal(fog.rgb, vec3(0.0))))) {
        vec4 c = imageLoad(io_color, px);
        imageStore(io_color, px, vec4(c.rgb * fog.a + fog.rgb, c.a));
    }
}
