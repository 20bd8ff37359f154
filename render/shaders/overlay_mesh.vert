#version 450 core
// A coloured overlay mesh (the preview's deviation map), pulled a little towards the eye so it
// wins the depth test against the surface it lies on.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec4 a_color;
uniform mat4 u_view_projection;
uniform vec3 u_eye;
out vec4 v_color;
void main()
{
    vec3 to_eye = u_eye - a_position;
    float d = length(to_eye);
    vec3 p = a_position + (d > 0.0 ? to_eye / d * min(0.002 * d, 5.0) : vec3(0.0));
    v_color = a_color;
    gl_Position = u_view_projection * vec4(p, 1.0);
}
