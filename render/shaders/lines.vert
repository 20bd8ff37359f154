#version 450 core
// Overlay lines (wireframes): world positions, pulled a little towards the eye so that lines
// lying on a surface win the depth test against it.
layout(location = 0) in vec3 a_position;
uniform mat4 u_view_projection;
uniform vec3 u_eye;
void main()
{
    vec3 to_eye = u_eye - a_position;
    float d = length(to_eye);
    vec3 p = a_position + (d > 0.0 ? to_eye / d * min(0.002 * d, 5.0) : vec3(0.0));
    gl_Position = u_view_projection * vec4(p, 1.0);
}
