#version 450 core
// Per particle, what its billboard's light needs that does not depend on the eye
// (render/src/particle_light.hpp): its place in the attenuation buffer's grid, the terrain's
// shadow at its centre (as the CPU reference lights the point the particle stands for), the
// share of its own column that shades it, and the log gain of its own footprint in each light
// column of its window ([Shimada08] (7): what the buffer holds of its own cylinder there, taken
// out of a fragment's read).
//
// The own share (geometry::calibrated_own_share): the blue-noise sampler keeps the other
// particles away from each one, so the buffer's read at its centre falls short of the Medium's
// optical depth towards the sun by about the mass of that empty neighbourhood towards the sun.
// Half its own column made that up in a deep slab; in fog a particle or two deep (a valley
// lake), 2 to 3 times that. With a Medium, the share is measured: the one that makes the read at
// the centre the Medium's optical depth (sun_volume.glsl), within [kMinOwnShare, kMaxOwnShare]:
// below 0 where the footprints of the balls up-sun already read more than the Medium there.
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Particles { GpuParticle particles[]; };
uniform uint u_count;
uniform vec3 u_centre;
uniform sampler3D u_log_gamma;  // the attenuation buffer
uniform int u_calibrate;        // 1: a Medium to measure the own share against (sun_volume.glsl bound)
uniform vec3 u_sun_march;       // the sun's direction as the marches take it (sun_march_direction)
const float kMinOwnShare = -1.0;  // geometry::min_own_share
const float kMaxOwnShare = 4.0;   // geometry::max_own_share

void main()
{
    uint id = gl_GlobalInvocationID.x;
    if (id >= u_count)
        return;
    GpuParticle p = particles[id];
    vec3 g = grid_of(p.position_radius.xyz), self_grid = shadow_grid(g);
    // The exponential map alone (terrain_shadow.glsl): bound by the sharp map as the froxels and
    // the layers are, the particles inside the canyon's fog went from 4.2 to 8.0 % off the
    // reference, darker where they were already 3 % too dark.
    particle_lights[id].grid_visible =
        vec4(self_grid, esm_visibility(p.position_radius.xyz + u_centre, u_ts_bias));
    Ball ball = ball_of(p);
    float share = kOwnShare;
    if (u_calibrate != 0) {
        float tau = medium_sun_optical_depth(p.position_radius.xyz + u_centre, u_sun_march, 0.5);
        float others = particle_log_gamma(u_log_gamma, g, self_grid, ball);
        float own = own_column_log_gain(g, self_grid, ball) *
            own_share_at(p.position_radius.xyz, p.position_radius.xyz, p.position_radius.w, p.top_plane.xyz, 1.0);
        if (own < -1e-4 && tau >= 0.0 && tau < 1e30)  // not where the march gave no number
            share = clamp((-tau - others) / own, kMinOwnShare, kMaxOwnShare);
    }
    particle_lights[id].offset.y = floatBitsToUint(share);
    if (u_self_table == 0)
        return;
    ivec4 w = particle_lights[id].window;
    uint offset = particle_lights[id].offset.x;
    for (int j = 0; j < w.w; ++j)
        for (int i = 0; i < w.z; ++i)
            self_gains[offset + uint(j * w.z + i)] =
                column_self_log_gain(ivec2(w.x + i, w.y + j), self_grid, ball);
}
