#version 450 core
// The terrain's visibility of the sun (terrain_shadow.glsl) at given points, read back: what the
// froxels', the layers' and the particles' lighting takes there, for the tests against the
// heightfield's exact shadow.
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Points { vec4 points[]; };
layout(std430, binding = 1) writeonly buffer Visibility { float visibility[]; };
uniform int u_count;

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i < u_count)
        visibility[i] = terrain_visibility(points[i].xyz, u_ts_bias);
}
