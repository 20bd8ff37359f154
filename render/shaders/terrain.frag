#version 450 core
// Terrain: colour by height and slope, lit by the sun and a hemispherical sky, hazed with
// distance towards the horizon colour so that far ridges read as far.
in vec3 v_world;
in vec3 v_normal;
uniform vec3 u_eye;
uniform vec3 u_sun_direction;  // towards the sun, unit
uniform vec3 u_sun_radiance;
uniform vec3 u_ambient;
uniform vec3 u_sky_horizon;
uniform float u_z_min;
uniform float u_z_max;
uniform float u_haze_density;  // 1/m
out vec4 o_color;  // linear radiance (tonemap.frag makes it a colour)

vec3 albedo(float height01, float steepness)
{
    const vec3 valley = vec3(0.16, 0.26, 0.10);
    const vec3 slope = vec3(0.30, 0.32, 0.15);
    const vec3 upland = vec3(0.42, 0.40, 0.28);
    const vec3 rock = vec3(0.40, 0.36, 0.32);
    vec3 c = height01 < 0.5 ? mix(valley, slope, height01 * 2.0) : mix(slope, upland, height01 * 2.0 - 1.0);
    return mix(c, rock, smoothstep(0.18, 0.55, steepness));
}

void main()
{
    vec3 n = normalize(v_normal);
    float height01 = clamp((v_world.z - u_z_min) / max(u_z_max - u_z_min, 1e-3), 0.0, 1.0);
    vec3 base = albedo(height01, 1.0 - n.z);
    float direct = max(dot(n, u_sun_direction), 0.0);
    // The terrain's own shadow where the froxel fog built the sun's shadow map (terrain_shadow.glsl;
    // froxel_none.glsl without it).
    if (direct > 0.0)
        direct *= terrain_shadow(v_world, n);
    vec3 sky = u_ambient * (0.6 + 0.4 * n.z);
    vec3 radiance = base * (u_sun_radiance * direct + sky);
    float haze = 1.0 - exp(-length(v_world - u_eye) * u_haze_density);
    radiance = mix(radiance, u_sky_horizon, haze);
    o_color = vec4(radiance, 1.0);
}
