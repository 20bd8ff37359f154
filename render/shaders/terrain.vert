#version 450 core
layout(location = 0) in vec3 a_position;  // local metres, exaggeration applied
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec4 a_shade;  // the fog's tau_sun here (the Medium's, whether to refine it, the height fog's: GroundShade; 0: none)
uniform mat4 u_view_projection;
out vec3 v_world;
out vec3 v_normal;
out vec4 v_shade;
void main()
{
    v_shade = a_shade;
    v_world = a_position;
    v_normal = a_normal;
    gl_Position = u_view_projection * vec4(a_position, 1.0);
}
