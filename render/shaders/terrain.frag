#version 450 core
// Terrain: coloured by ground.glsl (height, slope, water), lit by the sun and a hemispherical
// sky, hazed with distance towards the horizon colour so that far ridges read as far. The sun
// comes through the fog above: the ground under it lies in its shade.
in vec3 v_world;
in vec3 v_normal;
in vec2 v_shade;  // the fog's tau_sun and whether to refine it (GroundShade, ground_shade.glsl)
uniform vec3 u_eye;
uniform vec3 u_sun_direction;  // towards the sun, unit
uniform vec3 u_sun_radiance;
uniform vec3 u_ambient;
uniform vec3 u_sky_horizon;
uniform float u_haze_density;  // 1/m
out vec4 o_color;  // linear radiance (tonemap.frag makes it a colour)

void main()
{
    vec3 n = normalize(v_normal);
    vec3 base = ground_albedo(v_world, n.z);
    float direct = max(dot(n, u_sun_direction), 0.0);
    // The terrain's own shadow where the froxel fog built the sun's shadow map (terrain_shadow.glsl;
    // froxel_none.glsl without it), and the fog's shade (ground_shade.glsl).
    if (direct > 0.0)
        direct *= terrain_shadow(v_world, n, u_sun_direction) * exp(-max(ground_sun_depth(v_world, v_shade), 0.0));
    vec3 sky = u_ambient * (0.6 + 0.4 * n.z);
    vec3 radiance = base * (u_sun_radiance * direct + sky);
    float haze = 1.0 - exp(-length(v_world - u_eye) * u_haze_density);
    radiance = mix(radiance, u_sky_horizon, haze);
    o_color = vec4(radiance, 1.0);
}
