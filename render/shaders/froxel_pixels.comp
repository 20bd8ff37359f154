#version 450 core
// The fog-aware apply's marches (froxel_march.glsl's froxel_marched_fog): u_stage 0, the
// coarsest grid's points (frame_grid at u_spacing) into o_fog (the grid's size), read or
// marched; u_stage 1, the points of the grid at u_spacing that froxel_upsample.comp listed,
// which march, into o_fog. One invocation a point, so that the marches run side by side: in the
// apply's own pass a marching pixel among pixels that do not held its neighbours' lanes
// (llvmpipe runs eight invocations as one). With u_edge_rays (the split pixels' marches,
// froxel_edges.comp), stage 1: each listed pixel marches the ray through the mean of its other
// side's samples to their depth (u_depth's r) into o_fog, or, listed with y | 0x8000, its first
// side's (their depth in u_depth's g, their offset in b and a) into o_first_fog; both over
// bounds of their stretch of the shell (u_edge_ray: the other side's offset in pixels, first,
// last).
layout(local_size_x = 64) in;
layout(rgba32f, binding = 0) writeonly uniform image2D o_fog;
layout(rgba32f, binding = 1) writeonly uniform image2D o_info;  // stage 0: the points' frame_point_info
layout(rgba32f, binding = 2) writeonly uniform image2D o_first_fog;
uniform int u_stage;
uniform int u_edge_rays;
uniform sampler2D u_edge_ray;
shared uint group_marched;

void main()
{
    if (gl_LocalInvocationIndex == 0u)
        group_marched = 0u;
    barrier();
    uint i = gl_GlobalInvocationID.x;
    // The pixel, and where its fog goes (its sample, or itself); one call of the march below,
    // which the compiler inlines whole (a second one doubled the program's compile time).
    ivec2 px = ivec2(-1), at = ivec2(-1);
    bool first_side = false;
    if (u_stage == 0) {
        ivec2 n = frame_grid(u_spacing);
        if (i < uint(n.x * n.y))
            at = ivec2(int(i) % n.x, int(i) / n.x);
    } else if (i < fm_listed) {
        at = ivec2(int(fm_pixels[i] & 0xffffu), int(fm_pixels[i] >> 16));
        first_side = u_edge_rays != 0 && at.y >= 0x8000;
        at.y &= 0x7fff;
    }
    if (at.x >= 0)
        px = frame_grid_pixel(at, u_spacing);
    if (px.x >= 0) {
        vec2 uv = frame_uv(px);
        vec2 shell = vec2(0.0);
        float depth;
        if (u_edge_rays != 0) {
            vec4 ray = texelFetch(u_edge_ray, px, 0);
            vec4 depths = texelFetch(u_depth, px, 0);
            uv += (first_side ? depths.zw : ray.xy) / vec2(u_size);
            depth = frame_view_depth(first_side ? depths.y : depths.x);
            shell = ray.zw;
        } else {
            depth = frame_depth(px);
            shell = u_fx_shell != 0 ? froxel_pixel_shell(px) : shell;
        }
        if (u_stage == 0)
            imageStore(o_info, at, frame_point_info(px, depth));
        bool resolved = u_stage == 0 && froxel_resolved(px, uv, depth);
        vec4 fog = resolved ? froxel_fog_at(uv, depth) : froxel_marched_fog(uv, depth, shell, u_edge_rays == 0);
        if (u_stage == 0 && !resolved)
            atomicAdd(group_marched, 1u);
        if (first_side)
            imageStore(o_first_fog, at, fog);
        else
            imageStore(o_fog, at, fog);
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u && group_marched > 0u)
        atomicAdd(fm_sampled, group_marched);
}
