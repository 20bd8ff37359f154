#version 450 core
// Per particle, what its billboard's light needs that does not depend on the eye
// (render/src/particle_light.hpp): its place in the attenuation buffer's grid, the terrain's
// shadow at its centre (as the CPU reference lights the point the particle stands for), and
// the log gain of its own footprint in each light column of its window ([Shimada08] (7):
// what the buffer holds of its own cylinder there, taken out of a fragment's read).
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Particles { GpuParticle particles[]; };
uniform uint u_count;
uniform vec3 u_centre;

void main()
{
    uint id = gl_GlobalInvocationID.x;
    if (id >= u_count)
        return;
    GpuParticle p = particles[id];
    vec3 self_grid = shadow_grid(grid_of(p.position_radius.xyz));
    // The exponential map alone (terrain_shadow.glsl): bound by the sharp map as the froxels and
    // the layers are, the particles inside the canyon's fog went from 4.2 to 8.0 % off the
    // reference, darker where they were already 3 % too dark.
    particle_lights[id].grid_visible =
        vec4(self_grid, esm_visibility(p.position_radius.xyz + u_centre, u_ts_bias));
    if (u_self_table == 0)
        return;
    ivec4 w = particle_lights[id].window;
    uint offset = particle_lights[id].offset.x;
    Ball ball = ball_of(p);
    for (int j = 0; j < w.w; ++j)
        for (int i = 0; i < w.z; ++i)
            self_gains[offset + uint(j * w.z + i)] =
                column_self_log_gain(ivec2(w.x + i, w.y + j), self_grid, ball);
}
