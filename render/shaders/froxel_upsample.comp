#version 450 core
// The fog-aware apply's fog for every point of the grid at u_spacing (frame_grid: every fourth
// or second pixel of every fourth or second row, or every pixel), into o_fog: the volume's
// lookup where its slices resolve the fog (froxel_resolved; those points listed for
// froxel_lookup.comp); the coarser grid's own (u_fx_samples: froxel_pixels.comp stage 0 at every
// eighth pixel, or this pass at every fourth or second) at its points; the mean of the coarser points around a point where they agree; the
// rest are listed to march their own rays (froxel_pixels.comp stage 1), one invocation each.
//
// The samples (the coarser points) around a pixel stand for it (froxel_upsampled) when its surface's depth and its
// stretch of the Medium's shell lie within theirs (a ridge or a thread of fog between them that
// they missed shows in its own depths, which the shell and the terrain give at full resolution)
// and the mean's error in the pixel's colour through the fog (its background radiance B: B T +
// S), estimated from the samples' second differences along the axes it lies between samples on,
// is no more than u_fx_upsample of its value. Judged by the samples' spread instead (the bound
// of the mean's error for any monotone change), a smooth gradient of the fog's depth over the
// terrain marched as well: 44.7 % of the default scene's pixels marched, 31.7 % so. Judged
// without B (the in-scattered light alone), the fog's faint threads over a bright ground marched
// for nothing.
layout(local_size_x = 32, local_size_y = 8) in;
layout(rgba32f, binding = 0) writeonly uniform image2D o_fog;
layout(rgba32f, binding = 1) writeonly uniform image2D o_info;
uniform sampler2D u_fx_samples;  // the grid at twice u_spacing (frame_grid)
uniform sampler2D u_fx_sample_info;  // its points' frame_point_info
uniform int u_fx_write_info;     // this grid's points' frame_point_info into o_info (a finer grid follows)
uniform float u_fx_upsample;     // the tolerance; 0: none, every pixel the volume does not resolve marches
uniform sampler2D u_background;  // the frame's linear radiance before the fog
shared uint group_upsampled;
// The points the volume's lookup resolves, listed for froxel_lookup.comp (FrameMarches' layout).
layout(std430, binding = 1) buffer FrameLookups {
    uvec4 fl_dispatch;  // groups of 64
    uint fl_listed;
    uint fl_unused[3];
    uint fl_points[];
};

// How far a pixel's depths may lie outside the range of its samples' (relative).
const float depth_margin = 0.02;

struct Range {
    float lo, hi;
};

void widen(inout Range r, float v)
{
    r.lo = min(r.lo, v);
    r.hi = max(r.hi, v);
}

bool within(float v, Range r) { return v >= r.lo * (1.0 - depth_margin) && v <= r.hi * (1.0 + depth_margin); }

// Sample c's fog over background b: what the pixel would show through it.
vec3 seen(ivec2 c, vec3 b)
{
    vec4 f = texelFetch(u_fx_samples, c, 0);
    return b * f.a + f.rgb;
}

// Point t of the grid at u_spacing (pixel px, its surface at `depth`; its frame_point_info `own`
// where u_fx_write_info made it) from the coarser grid's.
bool froxel_upsampled(ivec2 t, ivec2 px, float depth, vec4 own, out vec4 fog)
{
    fog = vec4(0.0, 0.0, 0.0, 1.0);
    if (!(u_fx_upsample > 0.0))
        return false;
    int coarse = 2 * u_spacing;
    // Per axis: the coarser point at t (an even one, or the frame's last) or the two around it.
    ivec2 hi = (t + 1) / 2;
    bvec2 on = frame_on_coarser(t, u_spacing);
    if (all(on)) {
        fog = texelFetch(u_fx_samples, hi, 0);
        return true;
    }
    ivec2 lo = ivec2(on.x ? hi.x : hi.x - 1, on.y ? hi.y : hi.y - 1);
    // Midway only: where the coarser grid's last point is clamped to the frame's edge, march.
    ivec2 below = frame_grid_pixel(lo, coarse), above = frame_grid_pixel(hi, coarse);
    if ((!on.x && above.x - px.x != px.x - below.x) || (!on.y && above.y - px.y != px.y - below.y))
        return false;
    Range depths = Range(3e38, 0.0), firsts = depths, lasts = depths, over = depths;
    vec4 sum = vec4(0.0);
    for (int k = 0; k < 4; ++k) {
        ivec2 c = ivec2((k & 1) == 0 ? lo.x : hi.x, (k >> 1) == 0 ? lo.y : hi.y);
        sum += texelFetch(u_fx_samples, c, 0);
        vec4 info = texelFetch(u_fx_sample_info, c, 0);
        widen(depths, info.x);
        widen(over, info.y);
        widen(firsts, info.z);
        widen(lasts, info.w);
    }
    fog = 0.25 * sum;  // a point met twice (t on one axis's coarser point) weighs twice
    vec3 b = max(texelFetch(u_background, px, 0).rgb, vec3(0.0));
    // The mean's error, from the coarser points' second differences along each axis t lies
    // between them on (half of the largest: a step between the two points gives its own error,
    // a smooth bend four times it; a gradient none).
    vec3 bend = vec3(0.0);
    ivec2 last = frame_grid(coarse) - 1;
    for (int axis = 0; axis < 2; ++axis) {
        if (on[axis])
            continue;
        for (int r = 0; r < (on[1 - axis] ? 1 : 2); ++r) {
            ivec2 across = axis == 0 ? ivec2(1, 0) : ivec2(0, 1);
            ivec2 p = axis == 0 ? ivec2(lo.x, r == 0 ? lo.y : hi.y) : ivec2(r == 0 ? lo.x : hi.x, lo.y);
            vec3 f0 = seen(clamp(p - across, ivec2(0), last), b), f1 = seen(p, b), f2 = seen(p + across, b),
                 f3 = seen(clamp(p + 2 * across, ivec2(0), last), b);
            bend = max(bend, max(abs(f0 - 2.0 * f1 + f2), abs(f1 - 2.0 * f2 + f3)));
        }
    }
    if (!all(lessThanEqual(0.5 * bend, u_fx_upsample * (b * fog.a + fog.rgb))))
        return false;
    // The fog over the surface within the samples' to a metre.
    bool known = u_fx_write_info != 0;
    float own_over = known ? own.y : fog_over_surface(px, depth);
    if (!within(depth, depths) || !within(own_over, Range(over.lo - 1.0, over.hi + 1.0)))
        return false;
    if (u_fx_shell == 0)
        return true;
    vec2 shell = known ? own.zw : froxel_pixel_shell(px);
    return within(shell.x, firsts) && within(shell.y, lasts);
}

void main()
{
    if (gl_LocalInvocationIndex == 0u)
        group_upsampled = 0u;
    barrier();
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (all(lessThan(t, frame_grid(u_spacing)))) {
        ivec2 px = frame_grid_pixel(t, u_spacing);
        vec2 uv = frame_uv(px);
        float depth = frame_depth(px);
        vec4 own = vec4(0.0);  // what the finer grid judges this point by, where one follows
        if (u_fx_write_info != 0) {
            own = frame_point_info(px, depth);
            imageStore(o_info, t, own);
        }
        vec4 fog;
        if (u_fx_apply != 2 || froxel_resolved(px, uv, depth)) {
            uint i = atomicAdd(fl_listed, 1u);
            if (i % 64u == 0u)
                atomicAdd(fl_dispatch.x, 1u);
            fl_points[i] = uint(t.x) | (uint(t.y) << 16);
        } else if (froxel_upsampled(t, px, depth, own, fog)) {
            imageStore(o_fog, t, fog);
            if (!all(frame_on_coarser(t, u_spacing)))  // not a coarser point's own pixel
                atomicAdd(group_upsampled, 1u);
        } else {
            fm_list(uint(t.x) | (uint(t.y) << 16), 64u);
        }
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u && group_upsampled > 0u)
        atomicAdd(fm_upsampled, group_upsampled);
}
