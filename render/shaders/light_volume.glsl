// Library (after medium_shell.glsl): the baked light-transport volume
// (geometry::LightVolume, kiri/geometry/medium/light_volume.hpp), the lighting model's `baked`
// multiple scattering. Per cell the spherical-harmonic moments L_lm of the light scattered at
// least once, for a sun of unit radiance; the light it scatters towards o is
// sum_l g^l sum_m L_lm Y_lm(o) (Funk-Hecke, exact per band). The cells follow the shell: (x, y)
// on a regular grid, h = (z - floor) / (top - floor) of the Medium's column (its top raised to the
// height fog's where that is higher, its floor lowered to the ground where the height fog lies
// under it: LightVolume::shell) in nz levels.
// Stored in a 2D array texture, layer q nz + k holding moments 4q .. 4q + 3 of level k (RGBA32F,
// linear in x and y, clamped to the edge: the CPU's trilinear between cell centres, the levels
// blended here). LightVolumeTexture (light_volume_texture.hpp) sets the uniforms.
uniform int u_lv_on;
uniform sampler2DArray u_lv_moments;
uniform vec4 u_lv_rect;            // x0, y0, 1 / (nx dx), 1 / (ny dy)
uniform int u_lv_levels;           // nz
uniform int u_lv_bands;            // [1, 8]
uniform float u_lv_column_extinction;  // > 0: the moments are over the cells' column_scale
uniform vec4 u_lv_haze;  // the height fog the cells reach up into: extinction (0: none), base, scale height, top
// The cells' floors where the height fog lies under the Medium's floor (LightVolume::floors):
// u_lv_floors_n samples spanning the cells' rectangle (texel (a, b) is sample (a, b)); (0, 0): none.
uniform sampler2D u_lv_floors;
uniform ivec2 u_lv_floors_n;
// K_l^m = sqrt((2l + 1) / (4 pi) (l - m)! / (l + m)!), times sqrt(2) for m > 0, at [l 8 + m]
// (LightVolumeTexture::bind computes them once, as geometry::real_spherical_harmonics does).
uniform float u_lv_norms[64];

const int lv_max_bands = 8;

// g^l Y_lm(d) at [l (l + 1) + m] for l < bands (geometry::LightVolume::phase_weights): the real
// orthonormal harmonics by the recurrences of geometry::real_spherical_harmonics (no
// Condon-Shortley phase; sin^m(theta) (cos, sin)(m phi) as (u.x + i u.y)^m).
void lv_phase_weights(vec3 d, float g, int bands, out float w[lv_max_bands * lv_max_bands])
{
    for (int q = 0; q < lv_max_bands * lv_max_bands; ++q)
        w[q] = 0.0;
    float len = length(d);
    vec3 u = len > 0.0 ? d / len : vec3(0.0, 0.0, 1.0);
    float x = clamp(u.z, -1.0, 1.0);
    float lobe = clamp(g, -0.999, 0.999);
    float pmm = 1.0, re = 1.0, im = 0.0;
    for (int m = 0; m < bands; ++m) {
        if (m > 0)
            pmm *= 2.0 * float(m) - 1.0;
        // P_l^m for l = m, m + 1, ...: p0 = P_(l-2), p1 = P_(l-1)
        float p1 = pmm, p0 = 0.0;
        float gl = 1.0;  // g^l from l = m (pow is undefined for g < 0)
        for (int i = 0; i < m; ++i)
            gl *= lobe;
        for (int l = m; l < bands; ++l) {
            float p = p1;
            if (l == m + 1)
                p = x * (2.0 * float(m) + 1.0) * pmm;
            else if (l > m + 1)
                p = ((2.0 * float(l) - 1.0) * x * p1 - float(l + m - 1) * p0) / float(l - m);
            if (l > m) {
                p0 = p1;
                p1 = p;
            }
            float a = u_lv_norms[l * lv_max_bands + m] * p * gl;
            if (m == 0) {
                w[l * (l + 1)] = a;
            } else {
                w[l * (l + 1) + m] = a * re;
                w[l * (l + 1) - m] = a * im;
            }
            gl *= lobe;
        }
        float r = re * u.x - im * u.y;
        im = re * u.y + im * u.x;
        re = r;
    }
}

// The light scattered at least once towards `towards` by fog of anisotropy g at (x, y) and
// shell height h, per unit sun radiance, times `scale` (geometry::LightVolume::in_scattered):
// >= 0, 0 without a volume or outside the shell (h < 0).
float lv_in_scattered(vec2 xy, float h, float scale, vec3 towards, float g)
{
    if (u_lv_on == 0 || !(h >= 0.0) || !(scale > 0.0))
        return 0.0;
    int bands = clamp(u_lv_bands, 1, lv_max_bands);
    float w[lv_max_bands * lv_max_bands];
    lv_phase_weights(towards, g, bands, w);
    vec2 st = (xy - u_lv_rect.xy) * u_lv_rect.zw;
    float kz = clamp(clamp(h, 0.0, 1.0) * float(u_lv_levels) - 0.5, 0.0, float(u_lv_levels - 1));
    int k0 = int(floor(kz));
    int k1 = min(k0 + 1, u_lv_levels - 1);
    float fz = kz - float(k0);
    float sum = 0.0;
    for (int q = 0; 4 * q < bands * bands; ++q) {
        vec4 a = textureLod(u_lv_moments, vec3(st, float(q * u_lv_levels + k0)), 0.0);
        vec4 b = textureLod(u_lv_moments, vec3(st, float(q * u_lv_levels + k1)), 0.0);
        sum += dot(mix(a, b, fz), vec4(w[4 * q], w[4 * q + 1], w[4 * q + 2], w[4 * q + 3]));
    }
    return max(sum * scale, 0.0);
}

// LightVolume::floor_at: bilinear between the floors' samples (fetched, not filtered: the CPU's
// weights exactly); 1e30 without them.
float lv_floor_at(vec2 xy)
{
    if (u_lv_floors_n.x < 2 || u_lv_floors_n.y < 2)
        return 1e30;
    vec2 n = vec2(u_lv_floors_n - 1);
    vec2 g = clamp((xy - u_lv_rect.xy) * u_lv_rect.zw * n, vec2(0.0), n);
    ivec2 i = min(ivec2(g), u_lv_floors_n - 2);
    vec2 f = g - vec2(i);
    float a = texelFetch(u_lv_floors, i, 0).r, b = texelFetch(u_lv_floors, i + ivec2(1, 0), 0).r;
    float c = texelFetch(u_lv_floors, i + ivec2(0, 1), 0).r, d = texelFetch(u_lv_floors, i + ivec2(1, 1), 0).r;
    return mix(mix(a, b, f.x), mix(c, d, f.x), f.y);
}

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
    if (u_lv_on == 0 || !shell_covers(p.xy))
        return 0.0;
    vec4 column = shell_column(p.xy);  // floor, bottom, top, coverage
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
    return lv_in_scattered(p.xy, h, scale, towards, g);
}
