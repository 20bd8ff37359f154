// Library: the terrain's shadow from the sun, an exponential shadow map ([Annen08]) in
// light space, low-passed in log space (render/src/shadow_map_pass.cpp): a point at light depth
// d behind occluders at depth o is lit exp(k (o - d)), clamped to 1. The low-pass keeps the
// volume's shafts free of the flicker a sharp map gives.
uniform int u_ts_on;
uniform int u_ts_sun_set;        // the sun is below the horizon of a ground that runs on to it
uniform sampler2D u_ts_esm;      // k * occluder depth (m), low-passed in log space
uniform sampler2D u_ts_raw;      // occluder depth before the blur, a share of u_ts_depth
uniform mat4 u_ts_matrix;        // world -> shadow map [0, 1]^2 and light depth (m)
uniform float u_ts_k;            // 1/m
uniform float u_ts_bias;         // m: the receivers' offset towards the sun
uniform float u_ts_depth;        // m: the map's depth extent

// p in the map's frame: [0, 1]^2 across it, and its light depth in metres.
vec3 light_space(vec3 p) { return (u_ts_matrix * vec4(p, 1.0)).xyz; }

// The exponential map's visibility at a point l of the map's frame (the map on, the sun up).
float esm_visibility_at(vec3 l, float bias)
{
    if (any(lessThan(l.xy, vec2(0.0))) || any(greaterThan(l.xy, vec2(1.0))))
        return 1.0;
    float occluder = textureLod(u_ts_esm, l.xy, 0.0).r;
    // A receiver deeper than the map (the terrain's surround, beyond the box the map was made
    // of) is judged at the map's far end: shadowed by what the map holds, not by its emptiness.
    return clamp(exp(occluder - u_ts_k * (min(l.z, u_ts_depth) - bias)), 0.0, 1.0);
}

// The exponential map's visibility at p.
float esm_visibility(vec3 p, float bias)
{
    if (u_ts_on == 0)
        return 1.0;
    if (u_ts_sun_set != 0)
        return 0.0;
    return esm_visibility_at(light_space(p), bias);
}

// The map before its blur at a point l of the map's frame, its 4 texels weighed bilinearly
// (percentage closer), each lit where the point lies no more than `tolerance` metres behind its
// depth.
float sharp_visibility_at(vec3 l, float tolerance)
{
    vec2 f = fract(l.xy * vec2(textureSize(u_ts_raw, 0)) - 0.5);
    // The bilinear footprint's texels in one fetch: (0, 1), (1, 1), (1, 0), (0, 0).
    vec4 lit = step(vec4((min(l.z, u_ts_depth) - tolerance) / u_ts_depth), textureGather(u_ts_raw, l.xy));
    return mix(mix(lit.w, lit.z, f.x), mix(lit.x, lit.y, f.x), f.y);
}

// The map before its blur at a point l of the map's frame, its 4 texels weighed bilinearly, each
// lit where the point lies no more than five times `bias` (a texel) behind its depth: a texel's
// depth is its centre's and a slope rises within it, and air just over a slope lit at a grazing
// angle must stay lit (the lake's threads of fog in narrow valleys: two texels left some of them
// 10 to 20 % too dark). The blurred map spreads a wall's light into the air a few metres behind
// it: the thin shade along a canyon's wall under a sun a little lower than the wall is steep was
// lit (the views bench's canyon seen from inside its fog, the froxels 4.7 % off the reference, in
// bands along the wall; TerrainShadowProbeGl).
float hard_visibility_at(vec3 l, float bias) { return sharp_visibility_at(l, 5.0 * bias); }

// The terrain's visibility of the sun at a point of air (the fog's lighting): the exponential
// map's, its soft edge free of flicker, but no more than the sharp map's where that one sees the
// point behind the terrain. The point is taken into the map's frame once for both.
float terrain_visibility(vec3 p, float bias)
{
    if (u_ts_on == 0)
        return 1.0;
    if (u_ts_sun_set != 0)
        return 0.0;
    vec3 l = light_space(p);
    float v = esm_visibility_at(l, bias);
    return v > 0.0 ? min(v, hard_visibility_at(l, bias)) : v;
}

// The terrain's own shadow at a terrain point with normal n, the sun towards `sun`: the sharp
// map's, each texel lit where the point lies behind its depth by no more than the surface's own
// rise across the taps (a texel's depth is its centre's; the four taps reach a texel and a half
// away, where a slope turned from the sun by theta lies 1.5 texels x tan(theta) deeper) and half a
// texel.
float terrain_shadow(vec3 world, vec3 n, vec3 sun)
{
    if (u_ts_on == 0)
        return 1.0;
    if (u_ts_sun_set != 0)
        return 0.0;
    float c = clamp(dot(n, sun), 0.05, 1.0);
    float rise = 1.5 * sqrt(1.0 - c * c) / c;
    return sharp_visibility_at(light_space(world), u_ts_bias * (0.5 + rise));
}
