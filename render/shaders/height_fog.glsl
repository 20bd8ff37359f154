// Library: the height fog (geometry/src/volume/height_fog.cpp) as the reference evaluates it:
// its extinction and its optical depth in closed form (FroxelMedium::bind_height_fog sets it).
uniform vec4 u_hf;         // extinction, base, scale height, 0
uniform vec4 u_hf_extent;  // its horizontal extent: min x, min y, max x, max y

// The part of the line o + t d with t in [t0, t1] (narrowed in place) that lies over the
// rectangle [lo, hi] in x and y; false where none does. The height fog's extent, the Medium's
// grid (froxel_edges.comp) and the particles' fog rectangle (particles.frag) clip rays so.
bool line_over_rect(vec3 o, vec3 d, vec2 lo, vec2 hi, inout float t0, inout float t1)
{
    // Both axes at once, without a loop or a branch: llvmpipe runs eight invocations in lockstep,
    // and with the loop's early exits the froxels' marches and split pixels took 4-7 % longer.
    bvec2 level = lessThan(abs(d.xy), vec2(1e-20));  // the line does not move along this axis
    vec2 along = mix(d.xy, vec2(1.0), level);
    vec2 s0 = (lo - o.xy) / along, s1 = (hi - o.xy) / along;
    vec2 enter = mix(min(s0, s1), vec2(-3e38), level), leave = mix(max(s0, s1), vec2(3e38), level);
    t0 = max(t0, max(enter.x, enter.y));
    t1 = min(t1, min(leave.x, leave.y));
    return !any(bvec2(level.x && (o.x < lo.x || o.x > hi.x), level.y && (o.y < lo.y || o.y > hi.y))) && t1 > t0;
}

float height_fog_profile(float z)
{
    return z <= u_hf.y ? u_hf.x : u_hf.x * exp(-(z - u_hf.y) / u_hf.z);
}

float height_fog_sigma(vec3 p)
{
    if (u_hf.x <= 0.0 || any(lessThan(p.xy, u_hf_extent.xy)) || any(greaterThan(p.xy, u_hf_extent.zw)))
        return 0.0;
    return height_fog_profile(p.z);
}

// Optical depth of the height fog along the straight segment from a to b
// (geometry::HeightFog::optical_depth): the part over its extent, in closed form.
float height_fog_segment(vec3 a, vec3 b)
{
    if (u_hf.x <= 0.0)
        return 0.0;
    vec3 d = b - a;
    float u0 = 0.0, u1 = 1.0;
    if (!line_over_rect(a, d, u_hf_extent.xy, u_hf_extent.zw, u0, u1))
        return 0.0;
    float z0 = a.z + d.z * u0, z1 = a.z + d.z * u1, length_m = length(d) * (u1 - u0);
    float lo = min(z0, z1), hi = max(z0, z1);
    if (hi - lo < 1e-4 * u_hf.z)
        return height_fog_profile(0.5 * (z0 + z1)) * length_m;
    // Integral of sigma over [lo, hi] in z: constant under the base, exponential above it.
    float below = max(min(hi, u_hf.y) - lo, 0.0) * u_hf.x;
    float from = max(lo, u_hf.y);
    float above = hi > from ? height_fog_profile(from) * u_hf.z * (1.0 - exp(-(hi - from) / u_hf.z)) : 0.0;
    return (below + above) * length_m / (hi - lo);
}

// Optical depth of the height fog from p towards the sun s (unit, s.z > 0 for any light).
float height_fog_sun(vec3 p, vec3 s)
{
    if (u_hf.x <= 0.0)
        return 0.0;
    if (s.z <= 0.0)
        return 1e30;
    // To where the ray leaves the extent, or rises 30 scale heights above the base.
    float t = max(u_hf.y + 30.0 * u_hf.z - p.z, 0.0) / s.z;
    // Both axes at once, without a loop (line_over_rect says why).
    bvec2 moves = greaterThan(abs(s.xy), vec2(1e-20));
    vec2 exit = mix(u_hf_extent.xy, u_hf_extent.zw, greaterThan(s.xy, vec2(0.0)));
    vec2 to_exit = mix(vec2(3e38), max((exit - p.xy) / mix(vec2(1.0), s.xy, moves), vec2(0.0)), moves);
    t = min(t, min(to_exit.x, to_exit.y));
    return height_fog_segment(p, p + s * t);
}
