// Library (after particle_footprint.glsl and fog_lighting.glsl): a billboard's light. What
// depends on the particle alone comes from particle_light.comp, once per particle
// (render/src/particle_light.hpp); a fragment reads the attenuation buffer at its own point and
// takes the particle's own cylinder out with four reads of the particle's gain table.

struct ParticleLightRecord {
    vec4 grid_visible;  // shadow_grid of the centre (gx, gy, gw0); the terrain's visibility at the centre
    ivec4 window;       // first light column (i, j) of the gain table, columns along i and j
    uvec4 offset;       // x: the table's first entry; y: the bits of the particle's own share (particle_light.comp)
};
layout(std430, binding = 4) buffer ParticleLights { ParticleLightRecord particle_lights[]; };
layout(std430, binding = 5) buffer SelfGains { float self_gains[]; };

uniform int u_self_table;  // 0: the table is missing (too large), the gains are computed

// What a billboard's read at g holds of its own particle that it should not:
// self_log_gamma - kOwnShare own_column_log_gain (particle_footprint.glsl), the column gains read
// from the table. The read holds the own cylinder from the particle's depth on; the billboard
// takes kOwnShare of its footprint's column instead (billboard_log_gamma).
float table_own_excess(vec3 g, vec3 self_grid, ivec4 window, uint offset, float own_share)
{
    vec3 tx = linear_taps(g.x, u_grid_size.x), ty = linear_taps(g.y, u_grid_size.y), tz = linear_taps(g.z, u_grid_size.z);
    float sum = 0.0;
    for (int dj = 0; dj < 2; ++dj)
        for (int di = 0; di < 2; ++di) {
            ivec2 c = ivec2(di == 0 ? tx.x : tx.y, dj == 0 ? ty.x : ty.y);
            ivec2 local = c - window.xy;
            if (any(lessThan(local, ivec2(0))) || any(greaterThanEqual(local, window.zw)))
                continue;  // beyond the particle's radius: no deposit
            float gain = self_gains[offset + uint(local.y * window.z + local.x)];
            if (gain != 0.0)
                sum += (di == 0 ? 1.0 - tx.z : tx.z) * (dj == 0 ? 1.0 - ty.z : ty.z) * (self_depth_weight(c, self_grid, tz) - own_share) * gain;
        }
    return sum;
}

// log Gamma at grid point g on a particle's billboard (its record's self_grid, window and offset;
// its ball), attenuation_cpu.hpp's billboard_log_gamma: the trilinear read less
// the particle's own cylinder, plus own_share (own_share_at) of its footprint's column. The particle stands for
// the Medium around it, whose neighbourhood the blue-noise sampler left about one particle short,
// half of it towards the sun (docs/particles.md, "Lit as the Medium").
float billboard_log_gamma(sampler3D log_gamma, vec3 g, vec3 self_grid, ivec4 window, uint offset, Ball self_ball,
                          float own_share)
{
    float raw = texture(log_gamma, g / vec3(u_grid_size)).r;
#ifdef KIRI_SELF_TABLE
    // The table is there (the particles' program is compiled so): on a CPU rasteriser the other
    // branch's eight footprint gains would run for every fragment, masked or not.
    float excess = table_own_excess(g, self_grid, window, offset, own_share);
#else
    float excess = u_self_table != 0 ? table_own_excess(g, self_grid, window, offset, own_share)
                                     : self_log_gamma(g, self_grid, self_ball) - own_share * own_column_log_gain(g, self_grid, self_ball);
#endif
    return clamp(raw - excess, kMinLogGamma, 0.0);
}

uniform float u_anisotropy;
uniform vec3 u_sun_direction;
uniform vec3 u_sun_radiance;
uniform vec3 u_ambient;
uniform int u_octaves;

// geometry::billboard_own_share_at: the particle's share (kOwnShare, or its own measured by
// particle_light.comp) where the ray towards the sun (u_sun_direction) from `relative` stays in
// the fog for a radius, less where it leaves by the top sooner. top_plane: the top's height at
// the centre and its dz/dx, dz/dy (over 1e29: none); all relative to the cloud's centre.
float own_share_at(vec3 relative, vec3 centre, float radius, vec3 top_plane, float share)
{
    if (!(top_plane.x < 1e29) || !(radius > 0.0))
        return share;
    float under = top_plane.x + dot(top_plane.yz, relative.xy - centre.xy) - relative.z;
    float rise = u_sun_direction.z - dot(top_plane.yz, u_sun_direction.xy);
    return rise > 0.0 ? share * clamp(under / rise / radius, 0.0, 1.0) : share;
}

// The radiance a particle of albedo `albedo` scatters towards the eye at a point where the sun
// is seen through log_gamma (Gamma stands for exp(-tau_sun)) and the terrain's visibility
// sun_visible, at cos_theta between the view ray and the sun: geometry::fog_source, the model
// every fog renderer shares. u_octaves 0: the fitted orders of scattering; else octave i
// scatters a^i, sees b^i of the optical depth, has c^i g. Every term of a particle's light
// is here, so a change to it lands in one place.
vec3 particle_radiance(float log_gamma, float cos_theta, float albedo, float sun_visible)
{
    float sun = 0.0, a = 1.0, b = 1.0, c = 1.0;
    if (u_octaves == 0)
        sun = fitted_sun_scattering(cos_theta, u_anisotropy, albedo, -log_gamma, u_sun_direction.z);
    for (int i = 0; i < u_octaves; ++i, a *= 0.5, b *= 0.5, c *= 0.5)
        sun += a * henyey_greenstein(cos_theta, c * u_anisotropy) * exp(b * log_gamma);
    float sun_up = u_sun_direction.z > 0.0 ? sun_visible : 0.0;
    return clamp(albedo, 0.0, 1.0) * (3.14159265358979 * sun_up * sun * u_sun_radiance + u_ambient);
}
