#version 450 core
// Overlay meshes (overlay_mesh.hpp): world positions, optionally lifted towards the eye.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec4 a_color;
uniform mat4 u_view_projection;
uniform vec3 u_eye;
uniform float u_lift;
out vec3 v_world;
out vec3 v_normal;
out vec4 v_color;
void main()
{
    vec3 p = mix(a_position, u_eye, u_lift);
    v_world = p;
    v_normal = a_normal;
    v_color = a_color;
    gl_Position = u_view_projection * vec4(p, 1.0);
}
