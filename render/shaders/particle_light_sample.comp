#version 450 core
// log Gamma at given points on given particles' billboards, both as a billboard's fragment
// reads it (billboard_log_gamma: the particle's record and gain table) and with the own
// footprint computed in full from the particle (self_log_gamma, own_column_log_gain): the check that the
// per-particle light changes nothing (render/src/particle_light.hpp).
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Particles { GpuParticle particles[]; };
layout(std430, binding = 6) readonly buffer Queries { vec4 queries[]; };  // relative point; w: the slot's bits
layout(std430, binding = 7) writeonly buffer Results { vec2 results[]; };
uniform sampler3D u_log_gamma;
uniform uint u_count;

void main()
{
    uint id = gl_GlobalInvocationID.x;
    if (id >= u_count)
        return;
    vec4 q = queries[id];
    uint k = floatBitsToUint(q.w);
    GpuParticle p = particles[k];
    ParticleLightRecord record = particle_lights[k];
    vec3 g = grid_of(q.xyz);
    Ball ball = ball_of(p);
    float own_share = own_share_at(q.xyz, p.position_radius.xyz, p.position_radius.w, p.top_plane.xyz,
                                   uintBitsToFloat(record.offset.y));
    float by_table =
        billboard_log_gamma(u_log_gamma, g, record.grid_visible.xyz, record.window, record.offset.x, ball, own_share);
    float raw = texture(u_log_gamma, g / vec3(u_grid_size)).r;
    vec3 self_grid = shadow_grid(grid_of(p.position_radius.xyz));
    float direct = clamp(raw - self_log_gamma(g, self_grid, ball) + own_share * own_column_log_gain(g, self_grid, ball), kMinLogGamma, 0.0);
    results[id] = vec2(by_table, direct);
}
