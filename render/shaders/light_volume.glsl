// Library (after medium_shell.glsl): the baked light-transport volume
// (geometry::LightVolume, kiri/geometry/medium/light_volume.hpp), the lighting model's `baked`
// multiple scattering. Per cell the spherical-harmonic moments L_lm of the light scattered at
// least once, for a sun of unit radiance; the light it scatters towards o is
// sum_l g^l sum_m L_lm Y_lm(o) (Funk-Hecke, exact per band). The cells follow the shell: (x, y)
// on a regular grid, h = (z - floor) / (top - floor) of the Medium's column (its top raised to the
// height fog's where that is higher, its floor lowered to the ground where the height fog lies
// under it: LightVolume::shell) in nz levels.
// Stored in a 3D texture, slice q nz + k holding moments 4q .. 4q + 3 of level k (RGBA32F, linear,
// clamped to the edge: the CPU's trilinear between cell centres, each group of moments read
// within its own nz slices: one filtered read of both levels, where a 2D array's layers took two
// reads and a blend). With the terrain's shadow (LightVolume::class_means), one more group of
// slices after the moments' holds each cell's sunlit and shadowed parts' L_00 (x, y), and the
// lookup at a point scales the moments by its part's L_00 over the cell's. LightVolumeTexture
// (light_volume_texture.hpp) sets the uniforms.
uniform int u_lv_on;
uniform sampler3D u_lv_moments;
uniform vec4 u_lv_rect;            // x0, y0, 1 / (nx dx), 1 / (ny dy)
uniform int u_lv_levels;           // nz
uniform int u_lv_bands;            // [1, 8]
uniform float u_lv_column_extinction;  // > 0: the moments are over the cells' column_scale
uniform vec4 u_lv_haze;  // the height fog the cells reach up into: extinction (0: none), base, scale height, top
// The cells' floors where the height fog lies under the Medium's floor (LightVolume::floors):
// u_lv_floors_n samples spanning the cells' rectangle (texel (a, b) is sample (a, b)); (0, 0): none.
// Its green: the terrain's shadow's tops (LightVolume::shadow_tops) on u_lv_shadow_n samples
// spanning the same rectangle; (0, 0): none.
uniform sampler2D u_lv_floors;
uniform ivec2 u_lv_floors_n;
uniform ivec2 u_lv_shadow_n;
uniform int u_lv_groups;       // the moments texture's groups of nz slices
uniform int u_lv_parts_group;  // the group of the parts' L_00; -1: none
// K_l^m = sqrt((2l + 1) / (4 pi) (l - m)! / (l + m)!), times sqrt(2) for m > 0, at [l 8 + m]
// (LightVolumeTexture::bind computes them once, as geometry::real_spherical_harmonics does).
uniform float u_lv_norms[64];

const int lv_max_bands = 8;
const int lv_moment_texels = lv_max_bands * lv_max_bands / 4;  // 4 moments a texel

// Y_lm(u) of a unit direction u for l < lv_max_bands at [l (l + 1) + m], 4 a vec4 as the texture
// holds the moments: the real orthonormal harmonics by the recurrences of
// geometry::real_spherical_harmonics (no Condon-Shortley phase; sin^m(theta) (cos, sin)(m phi) as
// (u.x + i u.y)^m), spelled out. Written as loops over the bands, their array indexed by the
// loops' counters was kept in memory by llvmpipe, and the harmonics took more of a march with the
// baked light than its texture reads (that march twice one without the baked light).
void lv_harmonics(vec3 u, out vec4 w[lv_moment_texels])
{
    float x = clamp(u.z, -1.0, 1.0);
    vec2 e1 = u.xy;  // (u.x + i u.y)^m as (re, im)
    vec2 e2 = vec2(e1.x * u.x - e1.y * u.y, e1.x * u.y + e1.y * u.x);
    vec2 e3 = vec2(e2.x * u.x - e2.y * u.y, e2.x * u.y + e2.y * u.x);
    vec2 e4 = vec2(e3.x * u.x - e3.y * u.y, e3.x * u.y + e3.y * u.x);
    vec2 e5 = vec2(e4.x * u.x - e4.y * u.y, e4.x * u.y + e4.y * u.x);
    vec2 e6 = vec2(e5.x * u.x - e5.y * u.y, e5.x * u.y + e5.y * u.x);
    vec2 e7 = vec2(e6.x * u.x - e6.y * u.y, e6.x * u.y + e6.y * u.x);
    float p0_0 = 1.0;
    float p1_0 = x * 1.0 * p0_0;
    float p2_0 = (3.0 * x * p1_0 - 1.0 * p0_0) / 2.0;
    float p3_0 = (5.0 * x * p2_0 - 2.0 * p1_0) / 3.0;
    float p4_0 = (7.0 * x * p3_0 - 3.0 * p2_0) / 4.0;
    float p5_0 = (9.0 * x * p4_0 - 4.0 * p3_0) / 5.0;
    float p6_0 = (11.0 * x * p5_0 - 5.0 * p4_0) / 6.0;
    float p7_0 = (13.0 * x * p6_0 - 6.0 * p5_0) / 7.0;
    float p1_1 = 1.0;
    float p2_1 = x * 3.0 * p1_1;
    float p3_1 = (5.0 * x * p2_1 - 3.0 * p1_1) / 2.0;
    float p4_1 = (7.0 * x * p3_1 - 4.0 * p2_1) / 3.0;
    float p5_1 = (9.0 * x * p4_1 - 5.0 * p3_1) / 4.0;
    float p6_1 = (11.0 * x * p5_1 - 6.0 * p4_1) / 5.0;
    float p7_1 = (13.0 * x * p6_1 - 7.0 * p5_1) / 6.0;
    float p2_2 = 3.0;
    float p3_2 = x * 5.0 * p2_2;
    float p4_2 = (7.0 * x * p3_2 - 5.0 * p2_2) / 2.0;
    float p5_2 = (9.0 * x * p4_2 - 6.0 * p3_2) / 3.0;
    float p6_2 = (11.0 * x * p5_2 - 7.0 * p4_2) / 4.0;
    float p7_2 = (13.0 * x * p6_2 - 8.0 * p5_2) / 5.0;
    float p3_3 = 15.0;
    float p4_3 = x * 7.0 * p3_3;
    float p5_3 = (9.0 * x * p4_3 - 7.0 * p3_3) / 2.0;
    float p6_3 = (11.0 * x * p5_3 - 8.0 * p4_3) / 3.0;
    float p7_3 = (13.0 * x * p6_3 - 9.0 * p5_3) / 4.0;
    float p4_4 = 105.0;
    float p5_4 = x * 9.0 * p4_4;
    float p6_4 = (11.0 * x * p5_4 - 9.0 * p4_4) / 2.0;
    float p7_4 = (13.0 * x * p6_4 - 10.0 * p5_4) / 3.0;
    float p5_5 = 945.0;
    float p6_5 = x * 11.0 * p5_5;
    float p7_5 = (13.0 * x * p6_5 - 11.0 * p5_5) / 2.0;
    float p6_6 = 10395.0;
    float p7_6 = x * 13.0 * p6_6;
    float p7_7 = 135135.0;
    w[0] = vec4(u_lv_norms[0] * p0_0, u_lv_norms[9] * p1_1 * e1.y, u_lv_norms[8] * p1_0, u_lv_norms[9] * p1_1 * e1.x);
    w[1] = vec4(u_lv_norms[18] * p2_2 * e2.y, u_lv_norms[17] * p2_1 * e1.y, u_lv_norms[16] * p2_0, u_lv_norms[17] * p2_1 * e1.x);
    w[2] = vec4(u_lv_norms[18] * p2_2 * e2.x, u_lv_norms[27] * p3_3 * e3.y, u_lv_norms[26] * p3_2 * e2.y, u_lv_norms[25] * p3_1 * e1.y);
    w[3] = vec4(u_lv_norms[24] * p3_0, u_lv_norms[25] * p3_1 * e1.x, u_lv_norms[26] * p3_2 * e2.x, u_lv_norms[27] * p3_3 * e3.x);
    w[4] = vec4(u_lv_norms[36] * p4_4 * e4.y, u_lv_norms[35] * p4_3 * e3.y, u_lv_norms[34] * p4_2 * e2.y, u_lv_norms[33] * p4_1 * e1.y);
    w[5] = vec4(u_lv_norms[32] * p4_0, u_lv_norms[33] * p4_1 * e1.x, u_lv_norms[34] * p4_2 * e2.x, u_lv_norms[35] * p4_3 * e3.x);
    w[6] = vec4(u_lv_norms[36] * p4_4 * e4.x, u_lv_norms[45] * p5_5 * e5.y, u_lv_norms[44] * p5_4 * e4.y, u_lv_norms[43] * p5_3 * e3.y);
    w[7] = vec4(u_lv_norms[42] * p5_2 * e2.y, u_lv_norms[41] * p5_1 * e1.y, u_lv_norms[40] * p5_0, u_lv_norms[41] * p5_1 * e1.x);
    w[8] = vec4(u_lv_norms[42] * p5_2 * e2.x, u_lv_norms[43] * p5_3 * e3.x, u_lv_norms[44] * p5_4 * e4.x, u_lv_norms[45] * p5_5 * e5.x);
    w[9] = vec4(u_lv_norms[54] * p6_6 * e6.y, u_lv_norms[53] * p6_5 * e5.y, u_lv_norms[52] * p6_4 * e4.y, u_lv_norms[51] * p6_3 * e3.y);
    w[10] = vec4(u_lv_norms[50] * p6_2 * e2.y, u_lv_norms[49] * p6_1 * e1.y, u_lv_norms[48] * p6_0, u_lv_norms[49] * p6_1 * e1.x);
    w[11] = vec4(u_lv_norms[50] * p6_2 * e2.x, u_lv_norms[51] * p6_3 * e3.x, u_lv_norms[52] * p6_4 * e4.x, u_lv_norms[53] * p6_5 * e5.x);
    w[12] = vec4(u_lv_norms[54] * p6_6 * e6.x, u_lv_norms[63] * p7_7 * e7.y, u_lv_norms[62] * p7_6 * e6.y, u_lv_norms[61] * p7_5 * e5.y);
    w[13] = vec4(u_lv_norms[60] * p7_4 * e4.y, u_lv_norms[59] * p7_3 * e3.y, u_lv_norms[58] * p7_2 * e2.y, u_lv_norms[57] * p7_1 * e1.y);
    w[14] = vec4(u_lv_norms[56] * p7_0, u_lv_norms[57] * p7_1 * e1.x, u_lv_norms[58] * p7_2 * e2.x, u_lv_norms[59] * p7_3 * e3.x);
    w[15] = vec4(u_lv_norms[60] * p7_4 * e4.x, u_lv_norms[61] * p7_5 * e5.x, u_lv_norms[62] * p7_6 * e6.x, u_lv_norms[63] * p7_7 * e7.x);
}

// g^l Y_lm(d) (geometry::LightVolume::phase_weights) for l < bands, 0 past them.
void lv_phase_weights(vec3 d, float g, int bands, out vec4 w[lv_moment_texels])
{
    float len = length(d);
    lv_harmonics(len > 0.0 ? d / len : vec3(0.0, 0.0, 1.0), w);
    float lobe = clamp(g, -0.999, 0.999);
    float gl[lv_max_bands];  // g^l (pow is undefined for g < 0)
    gl[0] = 1.0;
    gl[1] = bands > 1 ? gl[0] * lobe : 0.0;
    gl[2] = bands > 2 ? gl[1] * lobe : 0.0;
    gl[3] = bands > 3 ? gl[2] * lobe : 0.0;
    gl[4] = bands > 4 ? gl[3] * lobe : 0.0;
    gl[5] = bands > 5 ? gl[4] * lobe : 0.0;
    gl[6] = bands > 6 ? gl[5] * lobe : 0.0;
    gl[7] = bands > 7 ? gl[6] * lobe : 0.0;
    w[0] *= vec4(gl[0], gl[1], gl[1], gl[1]);
    w[1] *= vec4(gl[2], gl[2], gl[2], gl[2]);
    w[2] *= vec4(gl[2], gl[3], gl[3], gl[3]);
    w[3] *= vec4(gl[3], gl[3], gl[3], gl[3]);
    w[4] *= vec4(gl[4], gl[4], gl[4], gl[4]);
    w[5] *= vec4(gl[4], gl[4], gl[4], gl[4]);
    w[6] *= vec4(gl[4], gl[5], gl[5], gl[5]);
    w[7] *= vec4(gl[5], gl[5], gl[5], gl[5]);
    w[8] *= vec4(gl[5], gl[5], gl[5], gl[5]);
    w[9] *= vec4(gl[6], gl[6], gl[6], gl[6]);
    w[10] *= vec4(gl[6], gl[6], gl[6], gl[6]);
    w[11] *= vec4(gl[6], gl[6], gl[6], gl[6]);
    w[12] *= vec4(gl[6], gl[7], gl[7], gl[7]);
    w[13] *= vec4(gl[7], gl[7], gl[7], gl[7]);
    w[14] *= vec4(gl[7], gl[7], gl[7], gl[7]);
    w[15] *= vec4(gl[7], gl[7], gl[7], gl[7]);
}

// The light scattered at least once towards `towards` by fog of anisotropy g at (x, y) and
// shell height h, per unit sun radiance, times `scale`, its magnitude that of the cells' `part`
// (0 sunlit, 1 in the terrain's shadow, -1 the whole cell: geometry::LightVolume::in_scattered_at
// and in_scattered): >= 0, 0 without a volume or outside the shell (h < 0).
float lv_in_scattered_part(vec2 xy, float h, float scale, vec3 towards, float g, int part)
{
    if (u_lv_on == 0 || !(h >= 0.0) || !(scale > 0.0))
        return 0.0;
    int bands = clamp(u_lv_bands, 1, lv_max_bands);
    vec4 w[lv_moment_texels];
    lv_phase_weights(towards, g, bands, w);
    vec2 st = (xy - u_lv_rect.xy) * u_lv_rect.zw;
    float kz = clamp(clamp(h, 0.0, 1.0) * float(u_lv_levels) - 0.5, 0.0, float(u_lv_levels - 1));
    float depth = float(u_lv_groups * u_lv_levels);  // the texture's slices
    // Every group, at constant indices (the weights past the bands are 0, their reads of later
    // slices clamped or the parts' finite values).
    vec4 m0 = textureLod(u_lv_moments, vec3(st, (kz + 0.5) / depth), 0.0);
    float sum = dot(m0, w[0]);
#define LV_TERM(q) sum += dot(textureLod(u_lv_moments, vec3(st, (float(q * u_lv_levels) + kz + 0.5) / depth), 0.0), w[q])
    LV_TERM(1); LV_TERM(2); LV_TERM(3); LV_TERM(4); LV_TERM(5); LV_TERM(6); LV_TERM(7);
    LV_TERM(8); LV_TERM(9); LV_TERM(10); LV_TERM(11); LV_TERM(12); LV_TERM(13); LV_TERM(14); LV_TERM(15);
#undef LV_TERM
    if (part >= 0 && u_lv_parts_group >= 0 && m0.x > 0.0) {
        vec2 means = textureLod(u_lv_moments, vec3(st, (float(u_lv_parts_group * u_lv_levels) + kz + 0.5) / depth), 0.0).xy;
        sum *= clamp((part == 1 ? means.y : means.x) / m0.x, 0.0, 64.0);
    }
    return max(sum * scale, 0.0);
}

float lv_in_scattered(vec2 xy, float h, float scale, vec3 towards, float g)
{
    return lv_in_scattered_part(xy, h, scale, towards, g, -1);
}

// Bilinear between the samples of the floors texture's `channel` on an n.x x n.y grid spanning
// the cells' rectangle (texel (a, b) is sample (a, b)), fetched, not filtered: the CPU's weights
// exactly (geometry::LightVolume's rectangle_grid_at); `none` without a grid.
float lv_rectangle_grid_at(vec2 xy, ivec2 n, int channel, float none)
{
    if (n.x < 2 || n.y < 2)
        return none;
    vec2 last = vec2(n - 1);
    vec2 g = clamp((xy - u_lv_rect.xy) * u_lv_rect.zw * last, vec2(0.0), last);
    ivec2 i = min(ivec2(g), n - 2);
    vec2 f = g - vec2(i);
    float a = texelFetch(u_lv_floors, i, 0)[channel], b = texelFetch(u_lv_floors, i + ivec2(1, 0), 0)[channel];
    float c = texelFetch(u_lv_floors, i + ivec2(0, 1), 0)[channel], d = texelFetch(u_lv_floors, i + ivec2(1, 1), 0)[channel];
    return mix(mix(a, b, f.x), mix(c, d, f.x), f.y);
}

// LightVolume::floor_at (red); 1e30 without floors.
float lv_floor_at(vec2 xy) { return lv_rectangle_grid_at(xy, u_lv_floors_n, 0, 1e30); }

// LightVolume::shadow_top_at (green); -1e30 without the terrain's shadow.
float lv_shadow_top_at(vec2 xy) { return lv_rectangle_grid_at(xy, u_lv_shadow_n, 1, -1e30); }

// The same at a point of the fog: h and column_scale from the Medium's column there
// (geometry::shell_height, LightVolume::column_scale); 0 outside the Medium's grid, and outside
// its column unless `into_column` (a layer's surface stands for the slab of fog under it and
// may lie on or a little above the top: it takes the column's nearest light).
// LIGHT_VOLUME 0: the variant of a froxel program for a Medium whose model is not baked
// (FroxelPass::Variants): llvmpipe runs a branch's code whether any lane takes it or not.
#ifndef LIGHT_VOLUME
#define LIGHT_VOLUME 1
#endif
float lv_in_scattered_at(vec3 p, vec3 towards, float g, bool into_column)
{
#if !LIGHT_VOLUME
    return 0.0;
#endif
    if (u_lv_on == 0)
        return 0.0;
    // Beyond the Medium's grid the grids hold their edge's values and the coverage is 0, as
    // geometry::Medium::column has them: the height fog there takes the edge cells' light, as the
    // CPU renderers give it (without a height fog nothing is lit there: no Medium).
    vec4 column = shell_column(p.xy);  // floor, bottom, top, coverage
    if (!shell_covers(p.xy))
        column.w = 0.0;
    // The cells' column (geometry::LightVolume::shell): the Medium's, down to the floors' grid
    // and up to the height fog's top.
    float floor_c = u_lv_haze.x > 0.0 ? min(column.x, lv_floor_at(p.xy)) : column.x;
    bool haze_above_floor = u_lv_haze.x > 0.0 && u_lv_haze.w > column.x;  // the Medium's floor: column_scale
    float top = u_lv_haze.x > 0.0 && u_lv_haze.w > floor_c ? max(column.z, u_lv_haze.w) : column.z;
    float thick = top - floor_c;
    if (into_column)
        p.z = clamp(p.z, column.x, column.z);
    if (!(thick > 0.0) || p.z < floor_c || p.z > top)
        return 0.0;
    float h = clamp((p.z - floor_c) / thick, 0.0, 1.0);
    float scale = 1.0;
    if (u_lv_column_extinction > 0.0) {  // LightVolume::column_scale
        float tau = u_lv_column_extinction * clamp(column.w, 0.0, 1.0) * max(column.z - column.x, 0.0);
        if (haze_above_floor) {  // the height fog's optical depth from the floor to its top: constant under its base
            float a = max(column.x, u_lv_haze.y);
            tau += u_lv_haze.x * max(min(u_lv_haze.w, u_lv_haze.y) - column.x, 0.0) +
                u_lv_haze.x * u_lv_haze.z * (exp(-(a - u_lv_haze.y) / u_lv_haze.z) - exp(-(u_lv_haze.w - u_lv_haze.y) / u_lv_haze.z));
        }
        scale = max(1.0 - exp(-tau), 1e-6);
    }
    int part = u_lv_parts_group >= 0 ? (p.z < lv_shadow_top_at(p.xy) ? 1 : 0) : -1;
    return lv_in_scattered_part(p.xy, h, scale, towards, g, part);
}
