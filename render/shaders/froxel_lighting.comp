#version 450 core
// Pass 2: the lighting per froxel (geometry/fog_lighting.hpp, docs/froxel.md) as J = S / sigma_t,
// the in-scattered radiance per unit of extinction, S = albedo sigma (E_sun V P + L_amb) summed
// over the media: V from the terrain's exponential shadow map (terrain_shadow.glsl), P the sun's
// phase through tau_sun over the scattering octaves, tau_sun the optical depth towards the sun
// (sun_volume.glsl: the height fog in closed form, the Medium from the sun volume). J is
// smooth where the density is not: it is what the temporal filter blends and what the apply
// looks up for each pixel's own density. Stored as (J, 1); (0, 0) where skipped: froxels
// without fog (standard slicing), or every froxel of a tile without fog (fog-aware, where the
// apply may look J up anywhere in a tile's range). J is as seen from the eye through the air
// (geometry/air_light.hpp), mixed towards the horizon's colour by the froxel's distance, as
// the layers, the particles, the terrain and the reference see theirs.
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(rgba16f, binding = 0) writeonly uniform image3D o_light;
uniform sampler3D u_density;
uniform vec3 u_jitter;
uniform float u_sun_jitter;
uniform vec3 u_sun_direction;
uniform vec3 u_sun_radiance;
uniform vec3 u_ambient;
uniform vec4 u_air;           // the air's radiance (rgb) and extinction (1/m; 0: none)
uniform vec2 u_albedo;        // medium, height fog
uniform vec2 u_anisotropy;    // medium, height fog
uniform int u_fog_shadows;
uniform int u_octaves;        // 1: single scattering
uniform int u_whole_tiles;    // light every froxel of a tile with fog, not only those with fog

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
    float haze = 1.0 - exp(-length(p - u_fx_eye) * u_air.w);
    // The phase by the direction of the rays through the froxel.
    float cos_theta = dot(normalize(p - u_fx_eye), u_sun_direction);
    // J is the light of fog. A point above the Medium's top or below its bottom (the tile's
    // jittered point above the fog its central ray is in, or a froxel without fog, whose J the
    // apply reads for fog its pixels find nearby) would take the sun's light in empty air,
    // unshadowed by the fog: under a grazing sun, all of the difference. It takes the sun's light
    // of its column's fog nearest to it.
    if (u_md_on != 0 && weights.x > 0.0 && shell_covers(p.xy)) {
        vec4 column = shell_column(p.xy);
        if (column.z > column.y)
            p.z = clamp(p.z, column.y, column.z - 1e-3 * (column.z - column.y));
    }
    float visible = terrain_visibility(p, u_ts_bias);
    float tau = u_fog_shadows != 0 && visible > 0.0 ? sun_optical_depth(p, u_sun_direction, u_sun_jitter) : 0.0;
    vec3 sun = 3.14159265358979 * u_sun_radiance * visible;  // pi sun: fog_lighting.hpp
    float sun_sine = normalize(u_sun_direction).z;
    vec3 s = u_albedo.x * weights.x *
            (sun * sun_scattering(cos_theta, u_anisotropy.x, u_albedo.x, tau, sun_sine, u_octaves) + u_ambient) +
        u_albedo.y * weights.y *
            (sun * sun_scattering(cos_theta, u_anisotropy.y, u_albedo.y, tau, sun_sine, u_octaves) + u_ambient);
    // The baked multiple scattering (light_volume.glsl; u_lv_on only with the Medium's model
    // `baked`): the light scattered at least once towards the eye, inside the Medium's shell,
    // not hidden by the terrain's shadow (it reaches the shadow from the sunlit fog beside it).
    if (u_lv_on != 0) {
        vec3 towards = normalize(u_fx_eye - p);
        float baked = 0.0;
        if (weights.x > 0.0)
            baked += u_albedo.x * weights.x * lv_in_scattered_at(p, towards, u_anisotropy.x, false);
        if (weights.y > 0.0)
            baked += u_albedo.y * weights.y * lv_in_scattered_at(p, towards, u_anisotropy.y, false);
        s += u_sun_radiance * baked;
    }
    imageStore(o_light, id, vec4(mix(s / (weights.x + weights.y), u_air.rgb, haze), 1.0));
}
