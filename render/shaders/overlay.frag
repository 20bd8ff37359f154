#version 450 core
// Overlay meshes: the vertex colour times the style colour; lit meshes get a soft two-sided
// sun shading that keeps a colour map readable (a colour is never darkened below 55 %).
in vec3 v_world;
in vec3 v_normal;
in vec4 v_color;
uniform vec4 u_color;
uniform int u_lit;
uniform vec3 u_eye;
uniform vec3 u_sun_direction;  // towards the sun, unit
out vec4 o_color;
void main()
{
    vec4 c = v_color * u_color;
    if (u_lit != 0) {
        vec3 n = normalize(v_normal);
        if (dot(n, u_eye - v_world) < 0.0)
            n = -n;  // seen from below (the camera inside the fog)
        c.rgb *= 0.55 + 0.45 * max(dot(n, u_sun_direction), 0.0);
    }
    o_color = c;
}
