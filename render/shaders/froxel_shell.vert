#version 450 core
// The Medium's shell (top, floor and walls, conservative) seen from the camera: its view depth.
layout(location = 0) in vec3 a_position;
uniform mat4 u_view_projection;
uniform vec3 u_eye;
uniform vec3 u_forward;
out float v_depth;
void main()
{
    v_depth = dot(a_position - u_eye, u_forward);
    gl_Position = u_view_projection * vec4(a_position, 1.0);
}
