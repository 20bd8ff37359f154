#version 450 core
// Particle billboards (Harris's render pass, [Shimada08] (5)-(6)): a camera-facing square of the
// particle's radius, drawn back to front in the order the CPU sorted (u_order). The attenuation
// buffer is read at the corners, not per fragment: log Gamma changes over the buffer's voxel,
// which a billboard seldom spans, and the rasteriser interpolates it over the billboard, so the
// fragments of the billboards' overdraw near the eye pay no lookup.
layout(std430, binding = 0) readonly buffer Particles { GpuParticle particles[]; };
layout(std430, binding = 2) readonly buffer Order { uint order[]; };
uniform mat4 u_view_projection;
uniform vec3 u_centre;  // the cloud's centre (positions are relative to it)
uniform vec3 u_camera_right;
uniform vec3 u_camera_up;
uniform sampler3D u_log_gamma;
uniform int u_lit;  // 0: no buffer (every particle fully lit)
out vec3 v_world;
out vec2 v_offset;      // in radii, (0, 0) at the centre
out float v_log_gamma;  // at the corner, the particle's own cylinder removed
flat out float v_sun_visible;  // the terrain's shadow (terrain_shadow.glsl) at the particle
flat out uint v_id;

void main()
{
    uint id = order[gl_InstanceID];
    GpuParticle particle = particles[id];
    vec4 p = particle.position_radius;
    vec2 corner = vec2((gl_VertexID & 1) == 0 ? -1.0 : 1.0, (gl_VertexID & 2) == 0 ? -1.0 : 1.0);
    vec3 relative = p.xyz + (corner.x * u_camera_right + corner.y * u_camera_up) * p.w;
    v_world = relative + u_centre;
    v_offset = corner;
    v_log_gamma = 0.0;
    if (u_lit != 0) {
        vec3 self_grid = shadow_grid(grid_of(p.xyz));
        v_log_gamma = particle_log_gamma(u_log_gamma, grid_of(relative), self_grid, vec3(p.w, particle.optics.xy));
    }
    // At the particle's centre, as the CPU reference lights the point the particle stands for
    // (a corner may dip into the ground and read as shadowed).
    v_sun_visible = terrain_visibility(p.xyz + u_centre, u_ts_bias);
    v_id = id;
    gl_Position = u_view_projection * vec4(v_world, 1.0);
}
