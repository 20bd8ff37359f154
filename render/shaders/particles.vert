#version 450 core
// Particle billboards (Harris's render pass, [Shimada08] (5)-(6)): a square of the particle's
// radius facing the eye, drawn back to front in the order the CPU sorted (u_order). The froxel fog in
// front of it (froxel_apply.glsl; none without it) is read at the corners and interpolated: at
// the billboard's one depth it changes over the froxels' tiles, and the fragments of the
// billboards' overdraw then pay no lookup. What the particle's light needs of the particle
// alone comes from its record (particle_light.comp); the sun's light through the attenuation
// buffer stays per fragment (particles.frag): the default scene's billboards (250 to 500 m)
// span one or two of the buffer's voxels, and read at the corners or the centre the particles'
// agreement with the reference fell by 0.5 to 2 points.
layout(std430, binding = 0) readonly buffer Particles { GpuParticle particles[]; };
layout(std430, binding = 2) readonly buffer Order { uint order[]; };
uniform uint u_first;  // of the sorted billboards, the first this draw takes
uniform mat4 u_view_projection;
uniform vec3 u_centre;  // the cloud's centre (positions are relative to it)
uniform vec3 u_camera_right;
uniform vec3 u_camera_up;
out vec3 v_relative;  // relative to the cloud's centre
out vec3 v_world;
out vec2 v_offset;    // in radii, (0, 0) at the centre
flat out vec4 v_grid_visible;  // the particle's record (particle_light.glsl)
flat out ivec4 v_window;
flat out uint v_table;
flat out vec3 v_optics;  // radius, tau, albedo
out vec4 v_fog;  // the froxel fog in front of the corner: in-scattered light, transmittance
flat out float v_baked;  // the baked light scattered at least once towards the eye, at the centre
uniform vec3 u_eye;

void main()
{
    // One indexed draw: vertex 4 q + c is corner c of billboard q (ParticlesPass::set_particles).
    uint id = order[u_first + uint(gl_VertexID >> 2)];
    vec4 p = particles[id].position_radius;
    vec2 corner = vec2((gl_VertexID & 1) == 0 ? -1.0 : 1.0, (gl_VertexID & 2) == 0 ? -1.0 : 1.0);
    // The disc faces the eye, not the screen's plane: it then covers the solid angle pi r^2 / d^2
    // its optical depth is spread over. A disc in the screen's plane covers cos(theta) of that at
    // theta off the view's axis, and drew the default view's fog 0.7 points too thin.
    vec3 to_eye = normalize(u_eye - (p.xyz + u_centre));
    vec3 right = cross(u_camera_up, to_eye);
    right = dot(right, right) > 1e-8 ? normalize(right) : u_camera_right;
    vec3 up = cross(to_eye, right);
    v_relative = p.xyz + (corner.x * right + corner.y * up) * p.w;
    v_world = v_relative + u_centre;
    v_offset = corner;
    v_grid_visible = particle_lights[id].grid_visible;
    v_window = particle_lights[id].window;
    v_table = particle_lights[id].offset.x;
    v_optics = vec3(p.w, particles[id].optics.xy);
    v_fog = froxel_fog(v_world);
    // The baked multiple scattering (light_volume.glsl) at the billboard's centre: its corners
    // may stand out of the Medium's shell, where the volume holds nothing.
    vec3 centre = p.xyz + u_centre;
    v_baked = u_lv_on != 0 ? lv_in_scattered_at(centre, normalize(u_eye - centre), u_anisotropy, false) : 0.0;
    gl_Position = u_view_projection * vec4(v_world, 1.0);
}
