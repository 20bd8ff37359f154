#version 450 core
// After the integration: per tile, whether the apply may read the volume there (one lookup,
// froxel_fog_at, as [Wronski14] applies it) or must march the pixels' own rays
// (froxel_marched_fog). A tile is read by the pixels within one tile of its centre (the bilinear
// lookup's four taps): where its own pixels and a pixel around cannot be resolved, the pixels
// between it and its neighbours march (w = 1): where its slices cannot resolve the fog along
// their rays:
//   - the fog's edge lies among them: some rays meet the shell and others not, or where they
//     enter or leave it spreads over more than u_edge_slices of the tile's slices;
//   - the fog changes across tiles faster than the bilinear lookup follows: the second
//     difference to the neighbouring tiles at the tile's slice ends, over 8 (the lookup's error
//     midway), exceeds u_tolerance in transmittance or in in-scattered radiance relative to
//     the tile's total;
//   - a pixel's surface lies in a slice too dense to interpolate within (transmittance falling
//     by more than u_tolerance * 8 across it, where the lookup is linear and the fog
//     exponential): a thin dense layer within a slice.
//   - the volume's lookup at the tile's central pixel misses its own ray's fog (marched) by more
//     than u_missed: where none of the above holds (w = -1), the pixels' program marches that ray
//     (froxel_pixels.comp, u_stage 2) and decides. Marched here, the march was compiled twice, for
//     this program and for the pixels': 1.2 s of a new user's first frame on llvmpipe.
// (A tap without slices as deep as a pixel's fog goes, a ground edge, is the apply's own check:
// froxel_resolved.)
// Needs froxel_common.glsl, froxel_medium.glsl, froxel_apply.glsl and froxel_frame.glsl before it;
// the tiles left to their central ray are listed in froxel_frame.glsl's FrameMarches (x | y << 16).
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) uniform image2D io_tiles;
uniform float u_tolerance;
uniform float u_edge_slices;

float max3(vec3 v) { return max(v.x, max(v.y, v.z)); }

// 1: march, 0: read the volume, -1: as the tile's central ray decides (froxel_pixels.comp).
float march(ivec2 t)
{
    vec2 range = fx_tile_range(t);
    float n = float(u_fx_size.z);
    vec2 cell = vec2(u_size) / vec2(u_fx_size.xy);
    ivec2 r0 = max(ivec2(floor(vec2(t) * cell)) - 1, ivec2(0));
    ivec2 r1 = min(ivec2(ceil(vec2(t + 1) * cell)) + 1, u_size);
    bool haze = u_hf.x > 0.0;
    int with_fog = 0, without_fog = 0;
    vec2 enter = vec2(3e38, 0.0), leave = vec2(3e38, 0.0), surface = vec2(3e38, 0.0);
    float deepest = 0.0;  // the farthest surface among the pixels
    float cut = 0.0;      // the pixels' taps' farthest range (froxel_pixel_cut), over the tiles around
    for (int k = 0; k < 9; ++k) {
        vec2 r = fx_tile_range(clamp(t + ivec2(k % 3 - 1, k / 3 - 1), ivec2(0), u_fx_size.xy - 1));
        cut = r.y > r.x ? max(cut, r.y) : cut;
    }
    for (int y = r0.y; y < r1.y; ++y)
        for (int x = r0.x; x < r1.x; ++x) {
            ivec2 px = ivec2(x, y);
            float end = min(frame_depth(px), u_fx_far);
            float fog_end = end;
            deepest = max(deepest, end);
            if (u_fx_shell != 0) {
                vec2 s = froxel_pixel_stretch(froxel_pixel_shell(px), end, cut);
                if (s.y > s.x) {
                    ++with_fog;
                    enter = vec2(min(enter.x, s.x), max(enter.y, s.x));
                    if (s.y < end) // the ray leaves the fog in front of its surface
                        leave = vec2(min(leave.x, s.y), max(leave.y, s.y));
                } else {
                    ++without_fog;
                }
                fog_end = s.y > s.x ? s.y : 0.0;
                if (haze)
                    fog_end = end;
            }
            if (end < u_fx_far && end <= fog_end)  // the surface lies in the fog
                surface = vec2(min(surface.x, end), max(surface.y, end));
        }
    if (with_fog > 0 && without_fog > 0)
        return 1.0;
    if (!(range.y > range.x))
        return 0.0;  // no fog here (a pixel's taps that do not reach its fog: froxel_resolved)
    if (enter.y > enter.x && (fx_slice_coordinate(enter.y, range) - fx_slice_coordinate(enter.x, range)) * n > u_edge_slices)
        return 1.0;
    if (leave.y > leave.x && (fx_slice_coordinate(leave.y, range) - fx_slice_coordinate(leave.x, range)) * n > u_edge_slices)
        return 1.0;
    // The bilinear lookup across tiles, at the tile's slice ends in front of its pixels'
    // surfaces; along each axis only where the three tiles' central rays all reach (the
    // fog-aware lookup hardly weighs a tile whose ground lies nearer).
    float scale = max(max3(froxel_column(t, range.y).rgb), 1e-6);
    ivec2 lo = ivec2(0), hi = u_fx_size.xy - 1;
    ivec2 x0 = clamp(t - ivec2(1, 0), lo, hi), x1 = clamp(t + ivec2(1, 0), lo, hi);
    ivec2 y0 = clamp(t - ivec2(0, 1), lo, hi), y1 = clamp(t + ivec2(0, 1), lo, hi);
    float ground = fx_tile_ground(t);
    float across = 0.999 * min(ground, min(fx_tile_ground(x0), fx_tile_ground(x1)));
    float down = 0.999 * min(ground, min(fx_tile_ground(y0), fx_tile_ground(y1)));
    for (int k = 0; k < u_fx_size.z; ++k) {
        if (fx_slice_depth(float(k) / n, range) > deepest)
            break;  // no pixel's surface lies behind this slice's start
        float d = fx_slice_depth(float(k + 1) / n, range);
        vec4 c = froxel_column(t, d);
        vec4 worst = vec4(0.0);
        if (d < across)
            worst = abs(froxel_column(x0, d) + froxel_column(x1, d) - 2.0 * c);
        if (d < down)
            worst = max(worst, abs(froxel_column(y0, d) + froxel_column(y1, d) - 2.0 * c));
        worst /= 8.0;
        if (worst.a > u_tolerance || max3(worst.rgb) > u_tolerance * scale)
            return 1.0;
    }
    // Surfaces inside a slice whose transmittance falls steeply.
    if (surface.y >= surface.x) {
        int k0 = int(fx_slice_coordinate(surface.x, range) * n), k1 = int(fx_slice_coordinate(surface.y, range) * n);
        for (int k = clamp(k0, 0, u_fx_size.z - 1); k <= clamp(k1, 0, u_fx_size.z - 1); ++k) {
            float before = k == 0 ? 1.0 : texelFetch(u_fx_volume, ivec3(t, k - 1), 0).a;
            if (before - texelFetch(u_fx_volume, ivec3(t, k), 0).a > 8.0 * u_tolerance)
                return 1.0;
        }
    }
    // Left to the tile's central pixel, marched as the apply would, against the lookup there
    // (froxel_pixels.comp, u_stage 2): a fog thinner than the slices are deep (a blanket seen from
    // afar, 15 km off through slices hundreds of metres deep) that the froxels' density samples
    // missed in some tiles, whose neighbours missed it too (so the lookup across them looked
    // smooth). Only a gross miss: the lookup's usual error (a few per cent) would send whole
    // views to march for nothing. With the eye outside the shell (u_fx_shell) only: the march then covers the
    // pixel's stretch in the shell alone, finely; from inside it spreads its steps over the whole
    // ray, and the volume is the better of the two.
    return u_fx_shell != 0 ? -1.0 : 0.0;
}

void main()
{
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(t, u_fx_size.xy)))
        return;
    vec4 tile = imageLoad(io_tiles, t);
    tile.w = march(t);
    imageStore(io_tiles, t, tile);
    if (tile.w < 0.0)
        fm_list(uint(t.x) | (uint(t.y) << 16), 64u);
}
