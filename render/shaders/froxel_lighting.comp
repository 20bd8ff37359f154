#version 450 core
// Pass 2: the lighting per froxel (geometry/fog_lighting.hpp, docs/froxel.md) as J = S / sigma_t,
// the in-scattered radiance per unit of extinction, S = albedo sigma (E_sun V P + L_amb) summed
// over the media: V from the terrain's exponential shadow map (terrain_shadow.glsl), P the sun's
// phase through tau_sun over the scattering octaves, tau_sun the optical depth towards the sun
// (height fog in closed form, the Medium in u_sun_steps steps to the edge of its box). J is
// smooth where the density is not: it is what the temporal filter blends and what the apply
// looks up for each pixel's own density. Stored as (J, 1); (0, 0) where skipped: froxels
// without fog (standard slicing), or every froxel of a tile without fog (fog-aware, where the
// apply may look J up anywhere in a tile's range).
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(rgba16f, binding = 0) writeonly uniform image3D o_light;
uniform sampler3D u_density;
uniform vec3 u_jitter;
uniform float u_sun_jitter;
uniform vec3 u_sun_direction;
uniform vec3 u_sun_radiance;
uniform vec3 u_ambient;
uniform vec2 u_albedo;        // medium, height fog
uniform vec2 u_anisotropy;    // medium, height fog
uniform int u_fog_shadows;
uniform int u_sun_steps;
uniform int u_octaves;        // 1: single scattering
uniform int u_whole_tiles;    // light every froxel of a tile with fog, not only those with fog
uniform vec3 u_box_min;       // the Medium's bounds
uniform vec3 u_box_max;
float sun_optical_depth(vec3 p)
{
    float tau = height_fog_sun(p, u_sun_direction);
    if (u_md_on == 0)
        return tau;
    // Exit of the Medium's box along the sun (slab test).
    vec3 inv = 1.0 / u_sun_direction;
    vec3 a = (u_box_min - p) * inv, b = (u_box_max - p) * inv;
    vec3 far_t = max(a, b), near_t = min(a, b);
    float t0 = max(max(near_t.x, near_t.y), max(near_t.z, 0.0));
    float t1 = min(min(far_t.x, far_t.y), far_t.z);
    if (!(t1 > t0))
        return tau;
    // Half the steps evenly up to twice where the sun leaves the fog's top above p (the grid's
    // top there): in a dense fog nearly all of tau_sun lies there, and with the scattering
    // octaves (exp(-tau / 4)) its error shows. The rest grow quadratically to the box's exit,
    // for fog the sun crosses farther away.
    float split = t0;
    if (u_sun_direction.z > 1e-3 && p.x >= u_md_origin.x && p.y >= u_md_origin.y && p.x <= u_md_last.x &&
        p.y <= u_md_last.y) {
        vec2 st = ((p.xy - u_md_origin) / (u_md_last - u_md_origin) * (u_md_cells - 1.0) + 0.5) / u_md_cells;
        vec4 c = textureLod(u_md_grid, st, 0.0);  // floor, bottom, top, coverage
        if (c.w > 0.0 && p.z < c.z)
            split = clamp(t0 + 2.0 * (c.z - max(p.z, c.y)) / u_sun_direction.z, t0, t1);
    }
    int near_steps = split > t0 ? max(u_sun_steps / 2, 1) : 0, far_steps = max(u_sun_steps - near_steps, 1);
    for (int k = 0; k < near_steps; ++k) {
        float s0 = mix(t0, split, float(k) / float(near_steps)), s1 = mix(t0, split, float(k + 1) / float(near_steps));
        tau += medium_sigma(p + u_sun_direction * mix(s0, s1, u_sun_jitter)) * (s1 - s0);
    }
    float n = float(far_steps);
    for (int k = 0; k < far_steps; ++k) {
        float u0 = float(k) / n, u1 = float(k + 1) / n;
        float s0 = split + (t1 - split) * u0 * u0, s1 = split + (t1 - split) * u1 * u1;
        tau += medium_sigma(p + u_sun_direction * mix(s0, s1, u_sun_jitter)) * (s1 - s0);
    }
    return tau;
}

void main()
{
    ivec3 id = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(id, u_fx_size)))
        return;
    vec4 density = texelFetch(u_density, id, 0);
    float sigma = density.x + density.y;
    vec2 range = fx_tile_range(id.xy);
    if (!(u_whole_tiles != 0 ? range.y > range.x : sigma > 0.0)) {
        imageStore(o_light, id, vec4(0.0));
        return;
    }
    // Where a froxel has no fog, J is that of the Medium (or of the height fog alone).
    vec2 weights = sigma > 0.0 ? density.xy : (u_md_on != 0 ? vec2(1.0, 0.0) : vec2(0.0, 1.0));
    vec2 uv = (vec2(id.xy) + u_jitter.xy) / vec2(u_fx_size.xy);
    float d0 = fx_slice_depth(float(id.z) / float(u_fx_size.z), range);
    float d1 = fx_slice_depth(float(id.z + 1) / float(u_fx_size.z), range);
    // Lit where the tile's central ray still is above the ground: froxels beyond it (pixels of
    // the tile see farther) take the light of the ray's last point before the ground, not that
    // of a point inside the hill.
    vec3 p = fx_world(uv, min(mix(d0, d1, density.z), 0.998 * fx_tile_ground(id.xy)));
    float cos_theta = dot(normalize(p - u_fx_eye), u_sun_direction);
    float visible = terrain_visibility(p, u_ts_bias);
    float tau = u_fog_shadows != 0 && visible > 0.0 ? sun_optical_depth(p) : 0.0;
    vec3 sun = 3.14159265358979 * u_sun_radiance * visible;  // pi sun: fog_lighting.hpp
    float sun_sine = normalize(u_sun_direction).z;
    vec3 s = u_albedo.x * weights.x *
            (sun * sun_scattering(cos_theta, u_anisotropy.x, u_albedo.x, tau, sun_sine, u_octaves) + u_ambient) +
        u_albedo.y * weights.y *
            (sun * sun_scattering(cos_theta, u_anisotropy.y, u_albedo.y, tau, sun_sine, u_octaves) + u_ambient);
    imageStore(o_light, id, vec4(s / (weights.x + weights.y), 1.0));
}
