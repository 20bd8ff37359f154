#version 450 core
// Pass 2b: temporal filtering of the lighting J. Each
// froxel's centre is reprojected into the previous frame's volume (its view, its tile ranges);
// the history found there is clamped to the range of the current froxel and its six
// neighbours (rejecting what moving sun, camera or fog changed) and blended with the current,
// jittered sample. No history (first frame, off-screen last frame, an empty tile then): the
// current sample alone.
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(rgba16f, binding = 0) writeonly uniform image3D o_resolved;
uniform sampler3D u_current;
uniform sampler3D u_history;
uniform sampler2D u_history_tiles;
uniform int u_history_valid;
uniform float u_weight;
uniform mat4 u_previous_view_projection;
uniform vec3 u_previous_eye;
uniform vec3 u_previous_forward;

void main()
{
    ivec3 id = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(id, u_fx_size)))
        return;
    vec4 current = texelFetch(u_current, id, 0);
    vec2 range = fx_tile_range(id.xy);
    if (u_history_valid == 0 || !(range.y > range.x)) {
        imageStore(o_resolved, id, current);
        return;
    }
    vec2 uv = (vec2(id.xy) + 0.5) / vec2(u_fx_size.xy);
    vec3 p = fx_world(uv, fx_slice_depth((float(id.z) + 0.5) / float(u_fx_size.z), range));
    vec4 clip = u_previous_view_projection * vec4(p, 1.0);
    vec2 previous_uv = clip.xy / clip.w * 0.5 + 0.5;
    if (clip.w <= 0.0 || any(lessThan(previous_uv, vec2(0.0))) || any(greaterThanEqual(previous_uv, vec2(1.0)))) {
        imageStore(o_resolved, id, current);
        return;
    }
    ivec2 tile = ivec2(previous_uv * vec2(u_fx_size.xy));
    vec2 previous_range = texelFetch(u_history_tiles, tile, 0).xy;
    float depth = dot(p - u_previous_eye, u_previous_forward);
    if (!(previous_range.y > previous_range.x) || depth < previous_range.x || depth > previous_range.y) {
        imageStore(o_resolved, id, current);
        return;
    }
    float w = fx_slice_coordinate(depth, previous_range) * float(u_fx_size.z) - 0.5;
    int k0 = clamp(int(floor(w)), 0, u_fx_size.z - 1), k1 = min(k0 + 1, u_fx_size.z - 1);
    vec4 h0 = texelFetch(u_history, ivec3(tile, k0), 0), h1 = texelFetch(u_history, ivec3(tile, k1), 0);
    vec4 history = mix(h0, h1, clamp(w - float(k0), 0.0, 1.0));
    vec4 lo = current, hi = current;
    const ivec3 offsets[6] = ivec3[](ivec3(1, 0, 0), ivec3(-1, 0, 0), ivec3(0, 1, 0), ivec3(0, -1, 0),
                                     ivec3(0, 0, 1), ivec3(0, 0, -1));
    for (int k = 0; k < 6; ++k) {
        ivec3 q = id + offsets[k];
        if (all(greaterThanEqual(q, ivec3(0))) && all(lessThan(q, u_fx_size))) {
            vec4 v = texelFetch(u_current, q, 0);
            if (v.a >= 0.0) {
                lo = min(lo, v);
                hi = max(hi, v);
            }
        }
    }
    // Neighbours and history that were not lit (a < 0) say nothing about J. Both parts of J (in
    // the terrain's shadow, the sun's share: froxel_lighting.comp) are blended.
    vec4 j = current;
    if (current.a >= 0.0 && h0.a >= 0.0 && h1.a >= 0.0)
        j = mix(current, clamp(history, lo, hi), u_weight);
    imageStore(o_resolved, id, j);
}
