#version 450 core
// The sun volume (sun_volume.glsl): per column and level of the Medium's shell
// (medium_shell.glsl), the Medium's optical depth towards the sun, marched to its box's exit in
// u_steps steps through the same density the froxels and the reference see (froxel_medium.glsl).
// The height fog's is added where it is read, in closed form at the point (sun_volume.glsl).
// Its second channel marks the points whose path grazes the grid's edge (sun_volume.glsl).
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(rg32f, binding = 0) writeonly uniform image3D o_tau;
uniform vec3 u_sun_direction;
uniform int u_steps;

void main()
{
    ivec3 id = ivec3(gl_GlobalInvocationID);
    ivec3 size = imageSize(o_tau);
    if (any(greaterThanEqual(id, size)))
        return;
    vec2 xy = shell_column_xy(id.xy, size.xy);
    vec4 column = shell_column(xy);
    vec3 p = vec3(xy, shell_height(float(id.z) / float(size.z - 1), column, float(size.z)));
    float graze = sun_path_grazes_a_wall(p, u_sun_direction, vec3(size)) ? 1.0 : 0.0;
    imageStore(o_tau, id, vec4(medium_sun_depth(p, u_sun_direction, u_steps, 0.5), graze, 0.0, 0.0));
}
