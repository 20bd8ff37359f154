// Library (after fog_partition.glsl, froxel_common.glsl, medium_shell.glsl and height_fog.glsl):
// the Medium (geometry/src/medium/medium.cpp) as the reference evaluates it, and the HG phase.
uniform int u_md_on;
uniform sampler2D u_md_noise;    // R32F: fog_noise_tile (linear, repeat)
uniform float u_md_extinction;   // sigma_t at density 1
uniform float u_md_top_density;
uniform float u_md_detail;
uniform float u_md_tile;         // metres per noise tile (8 detail_scale)
uniform float u_md_layers;       // l0: per-layer noise shift
uniform vec2 u_md_drift;         // wind * time
uniform float u_md_time;
uniform float u_md_half_life;

// The dissipation's factor at shell height h (geometry::Medium::dissipation).
float medium_dissipation(float h)
{
    return u_md_half_life > 0.0 && u_md_time > 0.0 ? exp2(-u_md_time / u_md_half_life * (1.0 + h)) : 1.0;
}

// d(p) and the shell's height fraction h there, in the column c (shell_column) over p.
float medium_density_in(vec3 p, vec4 c, out float h)
{
    h = 0.0;
    if (c.w <= 0.0 || p.z < c.x || p.z > c.z || !(c.z > c.y))
        return 0.0;
    h = clamp((p.z - c.y) / (c.z - c.y), 0.0, 1.0);
    float d = c.w * (1.0 - (1.0 - u_md_top_density) * h);
    if (u_md_detail > 0.0) {
        vec2 noise_st = (p.xy - u_md_drift) / u_md_tile + h * u_md_layers * vec2(0.137, 0.071);
        float n = textureLod(u_md_noise, noise_st, 0.0).r;
        d *= 1.0 - u_md_detail + u_md_detail * smoothstep(0.25, 0.75, n);
    }
    return d * medium_dissipation(h);
}

// d(p) and the shell's height fraction h there.
float medium_density_at(vec3 p, out float h)
{
    h = 0.0;
    if (u_md_on == 0 || !shell_covers(p.xy))
        return 0.0;
    return medium_density_in(p, shell_column(p.xy), h);
}

float medium_density(vec3 p)
{
    float h;
    return medium_density_at(p, h);
}

// All of the Medium: what dims the sun on its way to a point.
float medium_sigma(vec3 p) { return u_md_extinction * medium_density(p); }

// The part the froxels draw (fog_partition.glsl): all of it, or in combined mode their share
// by the distance from the eye, the height in the shell and the fog's thickness there.
float froxel_share_of(vec3 p, float d, float h, float thickness)
{
    return d > 0.0 ? u_md_extinction * d * froxels_share(distance(p, u_fx_eye), h, thickness) : 0.0;
}

// The same, in the column c over p (shell_column; u_md_on and shell_covers checked).
float froxel_sigma_in(vec3 p, vec4 c)
{
    float h;
    float d = medium_density_in(p, c, h);
    return froxel_share_of(p, d, h, c.z - c.x);
}

float froxel_sigma(vec3 p)
{
    if (u_md_on == 0 || !shell_covers(p.xy))
        return 0.0;
    return froxel_sigma_in(p, shell_column(p.xy));
}

// Henyey-Greenstein, g clamped strictly inside (-1, 1) like geometry::henyey_greenstein.
float hg_phase(float cos_theta, float g)
{
    g = clamp(g, -0.999, 0.999);
    float d = 1.0 + g * g - 2.0 * g * clamp(cos_theta, -1.0, 1.0);
    return (1.0 - g * g) / (12.566370614359172 * d * sqrt(d));
}

// The sun's phase and transmittance S (geometry::sun_scattering, fog_lighting.hpp): octaves 0,
// the fitted model; else over the scattering octaves, octave i scattering 2^-i of the sun
// through 2^-i of the optical depth with 2^-i of g.
float sun_scattering(float cos_theta, float g, float albedo, float tau, float sun_sine, int octaves)
{
    g = clamp(g, -0.999, 0.999);
    if (octaves == 0)
        return fitted_sun_scattering(cos_theta, g, albedo, tau, sun_sine);
    float sum = 0.0, weight = 1.0;
    for (int i = 0; i < octaves; ++i) {
        sum += weight * exp(-tau) * hg_phase(cos_theta, g);
        weight *= 0.5;
        tau *= 0.5;
        g *= 0.5;
    }
    return sum;
}
