// Library: the height fog (geometry/src/volume/height_fog.cpp) as the reference evaluates it:
// its extinction and its optical depth in closed form (FroxelMedium::bind_height_fog sets it).
uniform vec4 u_hf;         // extinction, base, scale height, 0
uniform vec4 u_hf_extent;  // its horizontal extent: min x, min y, max x, max y

// The part of the line o + t d with t in [t0, t1] (narrowed in place) that lies over the
// rectangle [lo, hi] in x and y; false where none does. The height fog's extent, the Medium's
// grid (froxel_edges.comp) and the particles' fog rectangle (particles.frag) clip rays so.
bool line_over_rect(vec3 o, vec3 d, vec2 lo, vec2 hi, inout float t0, inout float t1)
{
    for (int axis = 0; axis < 2; ++axis) {
        if (abs(d[axis]) < 1e-20) {
            if (o[axis] < lo[axis] || o[axis] > hi[axis])
                return false;
            continue;
        }
        float s0 = (lo[axis] - o[axis]) / d[axis], s1 = (hi[axis] - o[axis]) / d[axis];
        t0 = max(t0, min(s0, s1));
        t1 = min(t1, max(s0, s1));
    }
    return t1 > t0;
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
    for (int axis = 0; axis < 2; ++axis) {
        float lo = axis == 0 ? u_hf_extent.x : u_hf_extent.y, hi = axis == 0 ? u_hf_extent.z : u_hf_extent.w;
        if (abs(s[axis]) > 1e-20)
            t = min(t, max(((s[axis] > 0.0 ? hi : lo) - p[axis]) / s[axis], 0.0));
    }
    return height_fog_segment(p, p + s * t);
}
