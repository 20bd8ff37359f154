// Library: pass 4, the apply: the fog between the eye and a point of the frame.
//
// froxel_fog_at / froxel_fog read the integrated volume (pass 3) at a screen position and view
// depth: per tile between the ends of the two slices around that depth, bilinear across tiles
// (each with its own slices; fog-aware, tiles whose central ray meets the ground before that
// depth weigh little). That is Wronski's apply, what any surface (layers, particles) can read.
//
// The fog-aware apply for the terrain and the sky, which marches pixels' own rays where the
// volume cannot resolve their fog, is froxel_march.glsl.
// Needs froxel_common.glsl and froxel_medium.glsl before it.
uniform int u_fx_apply;               // 0: no froxel fog, 1: standard, 2: fog-aware
uniform sampler3D u_fx_volume;        // (in-scattered radiance, transmittance) at slice ends
uniform mat4 u_fx_view_projection;

vec4 froxel_column(ivec2 tile, float depth)
{
    vec2 range = fx_tile_range(tile);
    if (!(range.y > range.x) || depth <= range.x)
        return vec4(0.0, 0.0, 0.0, 1.0);
    float w = fx_slice_coordinate(depth, range) * float(u_fx_size.z);
    if (w >= float(u_fx_size.z))
        return texelFetch(u_fx_volume, ivec3(tile, u_fx_size.z - 1), 0);
    int k = int(floor(w));
    vec4 a = k == 0 ? vec4(0.0, 0.0, 0.0, 1.0) : texelFetch(u_fx_volume, ivec3(tile, k - 1), 0);
    vec4 b = texelFetch(u_fx_volume, ivec3(tile, k), 0);
    // Within a slice sigma and J are one (froxel_integrate.comp): the transmittance falls
    // exponentially and the in-scattered light follows it, so at the fraction x of the slice
    // T = T_a r^x and S = S_a + (S_b - S_a) (1 - r^x) / (1 - r), r = T_b / T_a. The linear mix is
    // their chord: at an optical depth of 2 a slice it was 54 % off mid-slice, in bands along
    // the depths of the slices' ends wherever the slices are deep in dense fog (from inside it).
    float x = w - float(k);
    float r = b.a / max(a.a, 1e-20);
    if (a.a > 1e-6 && r < 0.999) {
        float rx = pow(max(r, 1e-30), x);
        return vec4(a.rgb + (b.rgb - a.rgb) * ((1.0 - rx) / (1.0 - r)), a.a * rx);
    }
    return mix(a, b, x);
}

// (in-scattered radiance, transmittance) between the eye and screen point uv at view depth.
vec4 froxel_fog_at(vec2 uv, float depth)
{
    if (u_fx_apply == 0)
        return vec4(0.0, 0.0, 0.0, 1.0);
    vec2 p = uv * vec2(u_fx_size.xy) - 0.5;
    vec2 f = p - floor(p);
    ivec2 base = ivec2(floor(p));
    float reach = min(depth, u_fx_far) * 0.999;
    vec4 plain = vec4(0.0), aware = vec4(0.0);
    float aware_weight = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        ivec2 tile = clamp(base + o, ivec2(0), u_fx_size.xy - 1);
        float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        vec4 c = froxel_column(tile, depth);
        plain += w * c;
        float a = fx_tile_ground(tile) >= reach ? w : 1e-3 * w;
        aware += a * c;
        aware_weight += a;
    }
    return u_fx_apply == 2 && aware_weight > 1e-6 ? aware / aware_weight : plain;
}

vec4 froxel_fog(vec3 world)
{
    if (u_fx_apply == 0)
        return vec4(0.0, 0.0, 0.0, 1.0);
    vec4 clip = u_fx_view_projection * vec4(world, 1.0);
    if (!(clip.w > 1e-6))  // at the eye or behind it: no fog in front
        return vec4(0.0, 0.0, 0.0, 1.0);
    return froxel_fog_at(clip.xy / clip.w * 0.5 + 0.5, dot(world - u_fx_eye, u_fx_forward));
}
