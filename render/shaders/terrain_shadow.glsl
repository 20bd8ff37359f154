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

// The exponential map's visibility at p, a point at light depth d = l.z.
float esm_visibility(vec3 p, float bias)
{
    if (u_ts_on == 0)
        return 1.0;
    if (u_ts_sun_set != 0)
        return 0.0;
    vec3 l = (u_ts_matrix * vec4(p, 1.0)).xyz;
    if (any(lessThan(l.xy, vec2(0.0))) || any(greaterThan(l.xy, vec2(1.0))))
        return 1.0;
    float occluder = textureLod(u_ts_esm, l.xy, 0.0).r;
    // A receiver deeper than the map (the terrain's surround, beyond the box the map was made
    // of) is judged at the map's far end: shadowed by what the map holds, not by its emptiness.
    return clamp(exp(occluder - u_ts_k * (min(l.z, u_ts_depth) - bias)), 0.0, 1.0);
}

// The map before its blur at p, 4 texels weighed bilinearly (each lit where p lies no more than
// twice `bias` behind its depth: a texel's depth is its centre's, and a slope rises within it): a point of air a few metres behind its occluder, the thin shade along
// a canyon's wall under a sun just lower than the wall is steep, whose shadow the blurred map
// spreads the wall's light into (it judged 28 of 29 such points lit; the views bench's canyon
// seen from inside its fog, up to 20 % too bright in bands along the wall).
float hard_visibility(vec3 p, float bias)
{
    vec3 l = (u_ts_matrix * vec4(p, 1.0)).xyz;
    vec2 size = vec2(textureSize(u_ts_raw, 0));
    vec2 t = l.xy * size - 0.5, f = fract(t);
    ivec2 base = ivec2(floor(t));
    float d = min(l.z, u_ts_depth) - 2.0 * bias, lit = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        float occluder = texelFetch(u_ts_raw, clamp(base + o, ivec2(0), ivec2(size) - 1), 0).r * u_ts_depth;
        lit += d <= occluder ? w : 0.0;
    }
    return lit;
}

// The terrain's visibility of the sun at a point of air (the fog's lighting): the exponential
// map's, its soft edge free of flicker, but no more than the sharp map's where that one sees the
// point behind the terrain.
float terrain_visibility(vec3 p, float bias)
{
    float v = esm_visibility(p, bias);
    return v > 0.0 && u_ts_on != 0 && u_ts_sun_set == 0 ? min(v, hard_visibility(p, bias)) : v;
}

// The terrain's own shadow at a terrain point with normal n: looked up a little off the surface
// (normal offset), so that the map's texels do not shadow the surface they were made of.
float terrain_shadow(vec3 world, vec3 n) { return esm_visibility(world + n * (2.0 * u_ts_bias), 0.0); }
