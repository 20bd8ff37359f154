#version 450 core
// tau_sun (sun_volume.glsl) at given points, read back: what the froxels' and the layers'
// lighting takes there, for the tests against the Medium's integral.
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Points { vec4 points[]; };
layout(std430, binding = 1) writeonly buffer Depths { float depths[]; };
uniform vec3 u_sun_direction;
uniform int u_count;

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i < u_count)
        depths[i] = sun_optical_depth(points[i].xyz, u_sun_direction, 0.5);
}
