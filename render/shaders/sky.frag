#version 450 core
// Sky: a gradient from the horizon to the zenith plus a soft glow around the sun. Below the
// horizon, the ground beyond the surround: flat at its base level to the horizon, coloured by
// ground.glsl, lit by the sun and the sky, hazed into the horizon's colour as terrain.frag hazes.
in vec2 v_ndc;
uniform mat4 u_inverse_view_projection;
uniform vec3 u_eye;
uniform vec3 u_sun_direction;  // towards the sun, unit
uniform vec3 u_sun_radiance;   // the sun's glow (0 without it)
uniform vec3 u_sun_light;      // the sun's radiance on the ground
uniform vec3 u_ambient;
uniform vec3 u_sky_zenith;
uniform vec3 u_sky_horizon;
uniform int u_ground;          // 1: a terrain with its surround is drawn
uniform float u_ground_z;      // m: the surround's base level, exaggeration applied
uniform float u_haze_density;  // 1/m
out vec4 o_color;  // linear radiance

void main()
{
    vec4 far_point = u_inverse_view_projection * vec4(v_ndc, 1.0, 1.0);
    vec3 direction = normalize(far_point.xyz / far_point.w - u_eye);
    float elevation = clamp(direction.z, -1.0, 1.0);
    vec3 sky = mix(u_sky_horizon, u_sky_zenith, pow(max(elevation, 0.0), 0.45));
    if (elevation < 0.0) {
        sky = u_sky_horizon * (1.0 + 0.3 * elevation);
        if (u_ground != 0 && u_eye.z > u_ground_z) {
            float t = (u_ground_z - u_eye.z) / direction.z;
            vec3 ground = ground_albedo(vec3(u_eye.xy + t * direction.xy, u_ground_z), 1.0) *
                (u_sun_light * max(u_sun_direction.z, 0.0) + u_ambient);
            o_color = vec4(mix(ground, u_sky_horizon, 1.0 - exp(-t * u_haze_density)), 1.0);
            return;
        }
    }
    float sun = max(dot(direction, u_sun_direction), 0.0);
    sky += u_sun_radiance * (0.02 * pow(sun, 8.0) + 0.25 * pow(sun, 400.0));
    o_color = vec4(sky, 1.0);
}
