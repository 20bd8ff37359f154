// Library: pass 4, the apply. A surface (terrain, sky, layers, particles) reads the integrated
// volume at its own screen position and view depth: per tile, between the ends of the two
// slices around that depth; across tiles, bilinear in the screen (each tile with its own
// slices). Fog-aware, a tile whose central ray meets the ground before that depth weighs
// little (it has no fog beyond its ground), and the terrain reads each tile at the depth where
// that tile's ray meets the terrain's own tangent plane: at grazing angles through a thin
// layer the fog to the ground varies smoothly across tiles, the fog at a fixed depth does not.
// Needs froxel_common.glsl before it.
uniform int u_fx_apply;               // 0: no froxel fog this frame, 1: standard, 2: fog-aware
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
    return mix(a, b, w - float(k));
}

// (in-scattered radiance, transmittance) between the eye and screen point uv at view depth.
// Of the four tiles around uv, those whose central ray reaches that depth before the ground
// weigh most: a tile whose ray stops at a nearer slope or ridge has no fog beyond it.
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
    return froxel_fog_at(clip.xy / clip.w * 0.5 + 0.5, dot(world - u_fx_eye, u_fx_forward));
}

// The fog in front of a terrain point with unit normal n (facing the camera).
vec4 froxel_fog_surface(vec3 world, vec3 n)
{
    if (u_fx_apply != 2)
        return froxel_fog(world);
    vec4 clip = u_fx_view_projection * vec4(world, 1.0);
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    float depth = dot(world - u_fx_eye, u_fx_forward);
    vec2 p = uv * vec2(u_fx_size.xy) - 0.5;
    vec2 f = p - floor(p);
    ivec2 base = ivec2(floor(p));
    float height = dot(world - u_fx_eye, n);  // < 0: the eye is on the lit side of the plane
    vec4 sum = vec4(0.0), plain = vec4(0.0);
    float weight = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        ivec2 tile = clamp(base + o, ivec2(0), u_fx_size.xy - 1);
        float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        float ground = fx_tile_ground(tile);
        // Where the tile's ray meets this point's tangent plane.
        float along = dot(fx_ray((vec2(tile) + 0.5) / vec2(u_fx_size.xy)), n);
        float plane = along < 0.0 && height < 0.0 ? height / along : 3e38;
        float tolerance = 0.1 * depth;
        float at = ground;                    // the same surface: the tile's own ground
        if (plane < ground - tolerance)
            at = plane;                       // this point stands in front of what the tile sees
        else if (ground < plane - tolerance)
            w *= 1e-3;                        // the tile sees something nearer that hides this point
        vec4 c = froxel_column(tile, at);
        sum += w * c;
        weight += w;
        plain += (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y) * froxel_column(tile, depth);
    }
    return weight > 1e-6 ? sum / weight : plain;
}

