#version 450 core
// The fog-aware apply's marches (froxel_march.glsl's froxel_marched_fog): u_stage 0, the
// coarsest grid's points (frame_grid at u_spacing) into o_fog (the grid's size), read or
// marched; u_stage 1, the points of the grid at u_spacing that froxel_upsample.comp listed,
// which march, into o_fog. One invocation a point, so that the marches run side by side: in the
// apply's own pass a marching pixel among pixels that do not held its neighbours' lanes
// (llvmpipe runs eight invocations as one). With u_split (the split pixels' marches,
// froxel_edges.comp), stage 1: each listed pixel's samples march their own rays (u_offsets) to
// their own depths (u_ms_depth) over bounds of their stretch of the shell (u_split_ray), an
// invocation a sample (a group: 64 / u_samples pixels; four marches in a row in one invocation
// left most of a GPU idle), and the pixel gets their mean as one fog over its resolved colour C:
// of the samples' colours B_s (u_ms_color; C their mean), mean(B_s T_s + S_s) = C T + S with
// T = mean(T_s) and S = mean(B_s T_s + S_s) - mean(B_s) T, into o_fog.
layout(local_size_x = 64) in;
layout(rgba32f, binding = 0) writeonly uniform image2D o_fog;
layout(rgba32f, binding = 1) writeonly uniform image2D o_info;  // stage 0: the points' frame_point_info
// u_stage 2: the classification's last test (froxel_classify.comp), one invocation a tile it left
// undecided (w = -1, listed in fm_pixels): the tile's central pixel marched against the volume's
// lookup there, w = 1 where they differ by more than u_missed (in transmittance, or in radiance
// relative to the tile's total), else 0. Here, in this program's one call of the march, so that
// llvmpipe compiles the march once. Bound in every stage alike (FroxelPass::bind_stage_inputs):
// llvmpipe compiles a variant of a program per set of bound images and textures.
layout(rgba32f, binding = 2) uniform image2D io_tiles;
uniform float u_missed;
uniform int u_stage;
uniform int u_split;
uniform sampler2D u_split_ray;
uniform sampler2DMS u_ms_depth;
uniform sampler2DMS u_ms_color;
uniform int u_samples;      // the frame's samples a pixel (u_split)
uniform vec2 u_offsets[8];  // each sample's offset from the pixel's centre (pixels)
shared uint group_marched;
shared vec4 group_sample_fog[64];         // u_split: each sample's B_s T_s + S_s and T_s
shared vec3 group_sample_background[64];  // and its B_s

// Bounds of the stretch of the shell of the ray through sample point px + offset: where the four
// pixels around the point all meet the shell, their rasterised entries and exits read at the
// point, widened by half their spread, within `bounds` (the split pixel's: those of the pixels
// around it); elsewhere `bounds`. Seen at a grazing angle the entry into a level top moves by
// hundreds of metres from one row of pixels to the next, and the steps spread over all the
// pixels' stretches lay far apart in the fog (the lake from afar: 2.4 % off the reference so,
// 2.1 % read at the point).
vec2 froxel_sample_stretch(ivec2 px, vec2 offset, vec2 bounds)
{
    if (u_fx_shell == 0)
        return bounds;
    vec2 q = vec2(px) + offset;
    ivec2 base = ivec2(floor(q));
    vec2 f = q - vec2(base);
    vec2 at = vec2(0.0), lo = vec2(3e38), hi = vec2(0.0);
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        vec2 c = froxel_pixel_shell(clamp(base + o, ivec2(0), u_size - 1));
        if (!(c.y > c.x))
            return bounds;
        at += (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y) * c;
        lo = min(lo, c);
        hi = max(hi, c);
    }
    return vec2(max(bounds.x, at.x - 0.5 * (hi.x - lo.x)), min(bounds.y, at.y + 0.5 * (hi.y - lo.y)));
}

void main()
{
    if (gl_LocalInvocationIndex == 0u)
        group_marched = 0u;
    barrier();
    uint i = gl_GlobalInvocationID.x;
    // u_split: the invocation's sample, and the lane of its pixel's first sample.
    int sample_index = 0;
    uint first_lane = gl_LocalInvocationIndex;
    if (u_split != 0) {
        uint per_group = uint(64 / u_samples), local = gl_LocalInvocationIndex / uint(u_samples);
        sample_index = int(gl_LocalInvocationIndex % uint(u_samples));
        first_lane = local * uint(u_samples);
        i = local < per_group ? gl_WorkGroupID.x * per_group + local : 0xffffffffu;
    }
    // The pixel, and where its fog goes (its point of the grid, or itself).
    ivec2 px = ivec2(-1), at = ivec2(-1);
    if (u_stage == 0) {
        ivec2 n = frame_grid(u_spacing);
        if (i < uint(n.x * n.y))
            at = ivec2(int(i) % n.x, int(i) / n.x);
    } else if (i < fm_listed) {
        at = ivec2(int(fm_pixels[i] & 0xffffu), int(fm_pixels[i] >> 16));
    }
    if (at.x >= 0)
        px = u_stage == 2 ? clamp(ivec2((vec2(at) + 0.5) * (vec2(u_size) / vec2(u_fx_size.xy))), ivec2(0), u_size - 1)
                          : frame_grid_pixel(at, u_spacing);
    vec4 fog = vec4(0.0, 0.0, 0.0, 1.0);
    if (px.x >= 0) {
        vec2 uv = frame_uv(px);
        vec2 shell = vec2(0.0);
        float depth;
        if (u_split != 0) {
            uv += u_offsets[sample_index] / vec2(u_size);
            depth = frame_view_depth(texelFetch(u_ms_depth, px, sample_index).r);
            shell = froxel_sample_stretch(px, u_offsets[sample_index], texelFetch(u_split_ray, px, 0).xy);
            // Its own fog before its surface: the pixels around it may all see another surface
            // (the nearer of two), or reach the fog's top farther on, and their stretches end
            // before its fog or after its fog's sunlit skin, most of a dense fog's light (the dense
            // lake from afar: 7 of its 20 pixels over 10 % off the reference). Begun earlier only
            // where the fog missed so would be opaque and its steps stay denser than the skin: the
            // estimate takes its column as level, and in thin fog the steps spread over air (the
            // ridge through the blanket: 0.51 -> 0.58 % begun earlier wherever the estimate's
            // entry lay before).
            vec4 skin;
            float through, sigma;
            float under = fog_before(uv, depth, through, skin, sigma);
            float entry = depth - under;  // where the ray meets the top of its fog
            float start = depth - 1.5 * under;
            if (under > 0.0 && sigma * (shell.x - entry) > 1.0 &&
                sigma * (min(shell.y, depth) - start) > float(u_fx_pixel_steps))
                shell.x = start;
            if (under > 0.0 && shell.y < entry)
                shell.y = depth;
        } else {
            depth = frame_depth(px);
            shell = u_fx_shell != 0 ? froxel_pixel_shell(px) : shell;
        }
        if (u_stage == 0)
            imageStore(o_info, at, frame_point_info(px, depth));
        bool resolved = u_stage == 0 && froxel_resolved(px, uv, depth);
        // One call of each: a copy of the march inlined costs llvmpipe a second of compiling.
        vec4 looked = resolved || u_stage == 2 ? froxel_fog_at(uv, depth) : vec4(0.0);
        fog = resolved ? looked : froxel_marched_fog(uv, depth, shell, u_split == 0);
        if (u_stage == 2) {
            vec3 c = froxel_column(at, fx_tile_range(at).y).rgb;
            float scale = max(max(c.x, max(c.y, c.z)), 1e-6);
            vec3 off = abs(looked.rgb - fog.rgb);
            vec4 tile = imageLoad(io_tiles, at);
            tile.w = abs(looked.a - fog.a) > u_missed || max(off.x, max(off.y, off.z)) > u_missed * scale ? 1.0 : 0.0;
            imageStore(io_tiles, at, tile);
        }
        if (u_stage == 0 && !resolved)
            atomicAdd(group_marched, 1u);
        if (u_split != 0) {
            vec3 b = texelFetch(u_ms_color, px, sample_index).rgb;
            group_sample_fog[gl_LocalInvocationIndex] = vec4(b * fog.a + fog.rgb, fog.a);
            group_sample_background[gl_LocalInvocationIndex] = b;
        }
    }
    barrier();
    if (u_split != 0 && px.x >= 0 && sample_index == 0) {
        // The pixel's samples' mean, summed in their order.
        vec3 lit = vec3(0.0), background = vec3(0.0);  // sums of B_s T_s + S_s and of B_s
        float through = 0.0;                           // of T_s
        for (int s = 0; s < u_samples; ++s) {
            vec4 f = group_sample_fog[first_lane + uint(s)];
            lit += f.rgb;
            background += group_sample_background[first_lane + uint(s)];
            through += f.a;
        }
        float n = float(u_samples);
        fog = vec4(lit / n - background / n * (through / n), through / n);
    }
    if (px.x >= 0 && sample_index == 0 && u_stage != 2)
        imageStore(o_fog, at, fog);
    if (gl_LocalInvocationIndex == 0u && group_marched > 0u)
        atomicAdd(fm_sampled, group_marched);
}
