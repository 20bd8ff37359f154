#version 450 core
// The fog each pixel of the last frame received (what the apply computed at its depth), in
// float, for tests and benchmarks against the reference.
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
    float depth = view_depth(px);
    vec4 fog;
    if (depth < 0.0) {
        fog = froxel_fog_at(uv, 3e38);  // sky: the whole column
    } else {
        // The surface's normal from its neighbours' depths, each axis from the side whose depth
        // is closer (no normals across silhouettes).
        vec3 p = surface_point(px, depth);
        vec3 axes[2];
        for (int a = 0; a < 2; ++a) {
            ivec2 step = a == 0 ? ivec2(1, 0) : ivec2(0, 1);
            float dp = view_depth(px + step), dm = view_depth(px - step);
            bool plus = dp > 0.0 && (dm < 0.0 || abs(dp - depth) <= abs(dm - depth));
            axes[a] = plus ? surface_point(px + step, dp) - p : p - surface_point(px - step, dm);
        }
        vec3 n = normalize(cross(axes[0], axes[1]));
        if (dot(n, p - u_fx_eye) > 0.0)
            n = -n;
        fog = froxel_fog_surface(p, n);
    }
    imageStore(o_fog, px, fog);
    imageStore(o_depth, px, vec4(depth));
}
