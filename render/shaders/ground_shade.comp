#version 450 core
// tau_sun (sun_volume.glsl: the Medium's marched, the height fog's in closed form) at each vertex
// of the terrain's mesh (GroundShade): terrain.frag lights the ground with the sun's e^-tau
// through the fog, as the reference does.
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Vertices { float vertices[]; };  // u_stride floats each, the position first
layout(std430, binding = 1) writeonly buffer Depths { float depths[]; };
uniform vec3 u_sun_direction;
uniform int u_vertices;
uniform int u_stride;

void main()
{
    int v = int(gl_GlobalInvocationID.x);
    if (v >= u_vertices)
        return;
    int k = u_stride * v;
    vec3 p = vec3(vertices[k], vertices[k + 1], vertices[k + 2]);
    depths[v] = sun_optical_depth(p, u_sun_direction, 0.5);
}
