#version 450 core
// Gamma at every particle's centre, read from the attenuation buffer as the billboards read it
// (trilinear, minus the particle's own cylinder): the per-particle illumination the benchmark
// scores against the exact Harris pass.
layout(local_size_x = 64) in;

struct GridParticle {
    vec4 grid;    // gx, gy, gz, gw0
    vec4 optics;  // radius, tau, albedo, 0
};
layout(std430, binding = 0) readonly buffer Particles { GridParticle particles[]; };
layout(std430, binding = 1) writeonly buffer Gammas { float gammas[]; };
uniform sampler3D u_log_gamma;
uniform uint u_count;

void main()
{
    uint id = gl_GlobalInvocationID.x;
    if (id >= u_count)
        return;
    GridParticle p = particles[id];
    gammas[id] = particle_gamma(u_log_gamma, p.grid.xyz, p.grid.xyw, p.optics.xyz);
}
