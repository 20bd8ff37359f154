#version 450 core
// Sky: a gradient from the horizon to the zenith plus a soft glow around the sun.
in vec2 v_ndc;
uniform mat4 u_inverse_view_projection;
uniform vec3 u_eye;
uniform vec3 u_sun_direction;  // towards the sun, unit
uniform vec3 u_sun_radiance;
uniform vec3 u_sky_zenith;
uniform vec3 u_sky_horizon;
out vec4 o_color;  // linear radiance

void main()
{
    vec4 far_point = u_inverse_view_projection * vec4(v_ndc, 1.0, 1.0);
    vec3 direction = normalize(far_point.xyz / far_point.w - u_eye);
    float elevation = clamp(direction.z, -1.0, 1.0);
    vec3 sky = mix(u_sky_horizon, u_sky_zenith, pow(max(elevation, 0.0), 0.45));
    if (elevation < 0.0)
        sky = u_sky_horizon * (1.0 + 0.3 * elevation);
    float sun = max(dot(direction, u_sun_direction), 0.0);
    sky += u_sun_radiance * (0.02 * pow(sun, 8.0) + 0.25 * pow(sun, 400.0));
    o_color = vec4(sky, 1.0);
}
