#version 450 core
// The fog each pixel of the last frame received (what the apply computes at its depth, the
// terrain's depth at the pixel's centre here), in float, for tests and benchmarks against the
// reference.
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) writeonly uniform image2D o_fog;
layout(r32f, binding = 1) writeonly uniform image2D o_depth;  // view depth; -1 for sky
uniform sampler2D u_depth;
uniform ivec2 u_size;
uniform float u_near_plane;  // of the frame's projection
uniform float u_far_plane;

float view_depth(ivec2 px)
{
    float d = texelFetch(u_depth, clamp(px, ivec2(0), u_size - 1), 0).r;
    if (d >= 1.0)
        return -1.0;
    float z = d * 2.0 - 1.0;
    return 2.0 * u_near_plane * u_far_plane / (u_far_plane + u_near_plane - z * (u_far_plane - u_near_plane));
}

vec3 surface_point(ivec2 px, float depth) { return fx_world((vec2(px) + 0.5) / vec2(u_size), depth); }

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= u_size.x || px.y >= u_size.y)
        return;
    vec2 uv = (vec2(px) + 0.5) / vec2(u_size);
    float d = texelFetch(u_depth, px, 0).r;
    float z = d * 2.0 - 1.0;
    float depth = d >= 1.0 ? -1.0 : 2.0 * u_near_plane * u_far_plane / (u_far_plane + u_near_plane - z * (u_far_plane - u_near_plane));
    imageStore(o_fog, px, froxel_pixel_fog(px, uv, depth < 0.0 ? 3e38 : depth));
    imageStore(o_depth, px, vec4(depth));
}
