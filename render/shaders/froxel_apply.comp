#version 450 core
// Pass 4 over the frame: the fog each pixel of the resolved linear-radiance frame (RGBA16F,
// before the tone map) gets at its depth: radiance T + in-scattered radiance. Counts the pixels
// that marched their own rays (FroxelStats::marched_pixels).
layout(local_size_x = 32, local_size_y = 8) in;
layout(rgba16f, binding = 0) uniform image2D io_color;
layout(std430, binding = 0) buffer Marched { uint marched; };
uniform sampler2D u_depth;
uniform ivec2 u_size;
uniform float u_near_plane;  // of the frame's projection
uniform float u_far_plane;
shared uint group_marched;

void main()
{
    if (gl_LocalInvocationIndex == 0u)
        group_marched = 0u;
    barrier();
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x < u_size.x && px.y < u_size.y) {
        vec2 uv = (vec2(px) + 0.5) / vec2(u_size);
        float d = texelFetch(u_depth, px, 0).r;
        float z = d * 2.0 - 1.0;
        float depth = d >= 1.0 ? 3e38 : 2.0 * u_near_plane * u_far_plane / (u_far_plane + u_near_plane - z * (u_far_plane - u_near_plane));
        if (u_fx_apply == 2 && !froxel_resolved(px, uv, depth))
            atomicAdd(group_marched, 1u);
        vec4 fog = froxel_pixel_fog(px, uv, depth);
        if (!(fog.a >= 1.0 && all(equal(fog.rgb, vec3(0.0))))) {
            vec4 c = imageLoad(io_color, px);
            imageStore(io_color, px, vec4(c.rgb * fog.a + fog.rgb, c.a));
        }
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u && group_marched > 0u)
        atomicAdd(marched, group_marched);
}
