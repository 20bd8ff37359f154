#version 450 core
// Gamma at every particle's centre, read from the attenuation buffer as the billboards read it
// (trilinear, minus the particle's own cylinder): the per-particle illumination the benchmark
// scores against the exact Harris pass.
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Particles { GpuParticle particles[]; };
layout(std430, binding = 1) writeonly buffer Gammas { float gammas[]; };
uniform sampler3D u_log_gamma;
uniform uint u_count;

void main()
{
    uint id = gl_GlobalInvocationID.x;
    if (id >= u_count)
        return;
    GpuParticle p = particles[id];
    vec3 g = grid_of(p.position_radius.xyz);
    gammas[id] = particle_gamma(u_log_gamma, g, shadow_grid(g), ball_of(p));
}
