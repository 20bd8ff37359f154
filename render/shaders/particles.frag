#version 450 core
// A particle billboard: opacity 1 - T from its Gaussian footprint, lit by the fog's shared model
// (geometry::fog_source, fog_lighting.hpp) with the sun seen through the attenuation buffer:
// Gamma at this fragment (the particle's own cylinder removed) stands for exp(-tau_sun), so
// octave i sees Gamma^(b^i); hazed with distance like the terrain, faded out where it meets the
// terrain (soft edge); in the terrain's shadow from the sun (the renderer's shadow map, as the
// froxels and the CPU reference see it). Blended back to front, premultiplied linear radiance:
// E_k = S_k + T_k E_(k-1) ([Shimada08] (5)), S_k = (1 - T) J.
layout(std430, binding = 0) readonly buffer Particles { GpuParticle particles[]; };
in vec3 v_relative;
in vec3 v_world;
in vec2 v_offset;
flat in float v_sun_visible;
in vec4 v_fog;
flat in uint v_id;
uniform sampler3D u_log_gamma;
uniform sampler2D u_depth;       // the terrain's depth, full resolution
uniform int u_lit;               // 0: no buffer (every particle fully lit)
uniform float u_near;
uniform float u_far;
uniform float u_soft_edge;       // metres
uniform float u_anisotropy;
uniform vec3 u_eye;
uniform vec3 u_sun_direction;
uniform vec3 u_sun_radiance;
uniform vec3 u_ambient;
uniform vec3 u_sky_horizon;
uniform float u_haze_density;
uniform int u_octaves;
out vec4 o_color;

const float pi = 3.14159265358979;

float linear_depth(float d)
{
    float z = d * 2.0 - 1.0;
    return 2.0 * u_near * u_far / (u_far + u_near - z * (u_far - u_near));
}

void main()
{
    float x = length(v_offset);
    if (x >= 1.0)
        discard;
    GpuParticle p = particles[v_id];
    float alpha = 1.0 - exp(-p.optics.x * footprint_profile(x));
    float scene = linear_depth(texelFetch(u_depth, ivec2(gl_FragCoord.xy), 0).r);
    float here = linear_depth(gl_FragCoord.z);
    alpha *= u_soft_edge > 0.0 ? clamp((scene - here) / u_soft_edge, 0.0, 1.0) : step(here, scene);
    if (alpha < 1e-5)
        discard;
    float log_gamma = 0.0;
    if (u_lit != 0) {
        vec3 self_grid = shadow_grid(grid_of(p.position_radius.xyz));
        log_gamma = particle_log_gamma(u_log_gamma, grid_of(v_relative), self_grid, vec3(p.position_radius.w, p.optics.xy));
    }
    // geometry::fog_source: u_octaves 0, the fitted model (tau_sun = -log Gamma); else octave i
    // scatters a^i, sees b^i of the optical depth, has c^i g.
    vec3 view = normalize(v_world - u_eye);
    float cos_theta = dot(view, u_sun_direction);
    float sun = 0.0, a = 1.0, b = 1.0, c = 1.0;
    if (u_octaves == 0)
        sun = fitted_sun_scattering(cos_theta, u_anisotropy, p.optics.y, -log_gamma, u_sun_direction.z);
    for (int i = 0; i < u_octaves; ++i, a *= 0.5, b *= 0.5, c *= 0.5)
        sun += a * henyey_greenstein(cos_theta, c * u_anisotropy) * exp(b * log_gamma);
    float sun_up = u_sun_direction.z > 0.0 ? v_sun_visible : 0.0;
    vec3 radiance = clamp(p.optics.y, 0.0, 1.0) * (pi * sun_up * sun * u_sun_radiance + u_ambient);
    float haze = 1.0 - exp(-length(v_world - u_eye) * u_haze_density);
    radiance = mix(radiance, u_sky_horizon, haze);
    // The froxel fog in front of this billboard (read at its corners, particles.vert), as the
    // layers read it: over the already fogged frame, T C + a S composes to S + T (...).
    o_color = vec4((radiance * v_fog.a + v_fog.rgb) * alpha, alpha);
}
