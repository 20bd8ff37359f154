#version 450 core
// Particle billboards (Harris's render pass, [Shimada08] (5)-(6)): a square facing the eye that
// holds the cone of rays passing the particle, or the whole screen for a particle around the eye,
// drawn back to front in the order the CPU sorted (u_order). The froxel fog in
// front of it (froxel_apply.glsl; none without it) is read at the corners and interpolated: at
// the billboard's one depth it changes over the froxels' tiles, and the fragments of the
// billboards' overdraw then pay no lookup. What the particle's light needs of the particle
// alone comes from its record (particle_light.comp); the sun's light through the attenuation
// buffer stays per fragment (particles.frag): the default scene's billboards (250 to 500 m)
// span one or two of the buffer's voxels, and read at the corners or the centre the particles'
// agreement with the reference fell by 0.5 to 2 points.
layout(std430, binding = 0) readonly buffer Particles { GpuParticle particles[]; };
layout(std430, binding = 2) readonly buffer Order { uint order[]; };
#if LIGHT_VOLUME
layout(std430, binding = 3) readonly buffer BakedLights { vec4 baked_lights[]; };  // particle_baked.comp
#endif
uniform uint u_first;  // of the sorted billboards, the first this draw takes
uniform mat4 u_view_projection;
uniform vec3 u_centre;  // the cloud's centre (positions are relative to it)
uniform vec3 u_camera_right;
uniform vec3 u_camera_up;
out vec3 v_ray;       // from the eye through this corner
flat out vec3 v_centre;  // the particle's centre, from the eye
flat out vec4 v_grid_visible;  // the particle's record (particle_light.glsl)
flat out ivec4 v_window;
flat out uint v_table;
flat out float v_own_share;  // the share of its own column that shades it (particle_light.comp)
flat out vec3 v_optics;  // radius, tau times its gain (seen_gain), albedo
flat out float v_seen_tau;  // tau as the billboard draws it: with the part in the ground or cut off at a plane added
// The planes of the fog's floor under it (where the fog floats over the ground; below -1e29:
// none) and of its top (over 1e29: none): height at its centre relative to u_centre, dz/dx, dz/dy.
flat out vec3 v_floor_plane;
flat out vec3 v_top_plane;
out vec4 v_fog;  // the froxel fog in front of the corner: in-scattered light, transmittance
// The baked light scattered at least once towards the eye, at the centre, and its change with
// height (particle_baked.comp).
flat out float v_baked;
flat out vec3 v_baked_slope;  // d/dz, and the range it is extrapolated within
uniform vec3 u_eye;
// A frame drawn small draws every k-th billboard, sqrt(k) times as wide with the same optical
// depth: the same optical mass and cover (ParticlesPass::set_resolution); sqrt(k) here, 1 else.
uniform float u_radius_scale;
flat out float v_footprint_radius;  // the billboard's radius (the particle's light keeps its own)
flat out float v_depth_radius;      // the ball's extent along the rays (before widening)
flat out vec2 v_centre_ndc;         // the centre on the screen
uniform vec3 u_camera_forward;
uniform vec2 u_tan_half;  // tan of half the view's angle across and up
uniform float u_pixel_angle;  // the target's pixel across, in radians at the screen's centre
const float kWholeScreen = 1.5;  // a particle nearer than this many radii covers the screen
const float kMinPixels = 1.0;    // the narrowest footprint drawn, in pixels of radius

void main()
{
    // One indexed draw: vertex 4 q + c is corner c of billboard q (ParticlesPass::set_particles).
    uint id = order[u_first + uint(gl_VertexID >> 2)];
    vec4 p = particles[id].position_radius;
    vec2 corner = vec2((gl_VertexID & 1) == 0 ? -1.0 : 1.0, (gl_VertexID & 2) == 0 ? -1.0 : 1.0);
    vec3 centre_world = p.xyz + u_centre;
    vec3 from_eye = centre_world - u_eye;
    float d = length(from_eye);
    float r = p.w * u_radius_scale;
    // A footprint only a pixel or two across is sampled at a few pixels' centres, which catch
    // much or little of its mass as it falls: a far fog of small billboards drew as speckle
    // (thin fog over a plain, 20,000 billboards of a third of a pixel: 16.6 % off the reference).
    // Widened to kMinPixels pixels with its optical depth thinned to keep its mass, as splatting
    // low-passes a splat by the pixel's own footprint ([Zwicker01]); across the rays alone: the
    // ball keeps its depth, so the terrain hides as much of it (particles.frag).
    float widen = max(kMinPixels * u_pixel_angle * d / r, 1.0);
    v_depth_radius = r;
    r *= widen;
    vec4 centre_clip = u_view_projection * vec4(centre_world, 1.0);
    v_centre_ndc = centre_clip.xy / max(centre_clip.w, 1e-6);
    v_footprint_radius = r;
    v_centre = from_eye;
    vec3 corner_world;
    if (d > kWholeScreen * r) {
        // The disc faces the eye: it then covers the cone of rays passing within r of the
        // centre, once its radius is r d / sqrt(d^2 - r^2) (the fragments measure each ray's own
        // distance from the centre). A disc in the screen's plane covered cos(theta) of that at
        // theta off the view's axis, and drew the default view's fog 0.7 points too thin.
        vec3 to_eye = -from_eye / d;
        vec3 right = cross(u_camera_up, to_eye);
        right = dot(right, right) > 1e-8 ? normalize(right) : u_camera_right;
        vec3 up = cross(to_eye, right);
        float disc = r * d / sqrt(d * d - r * r);
        corner_world = centre_world + (corner.x * right + corner.y * up) * disc;
        v_ray = corner_world - u_eye;
        gl_Position = u_view_projection * vec4(corner_world, 1.0);
    } else {
        // The eye is in the particle or at its rim: every ray from it may cross the particle, so
        // it covers the whole screen (the fragments take the part of it in front of the eye).
        v_ray = u_camera_forward + corner.x * u_tan_half.x * u_camera_right + corner.y * u_tan_half.y * u_camera_up;
        vec3 ray = normalize(v_ray);
        corner_world = u_eye + ray * max(dot(from_eye, ray), 0.05 * r);  // in front of the eye
        gl_Position = vec4(corner, 0.0, 1.0);
    }
    v_grid_visible = particle_lights[id].grid_visible;
    v_window = particle_lights[id].window;
    v_table = particle_lights[id].offset.x;
    v_own_share = uintBitsToFloat(particle_lights[id].offset.y);
    v_optics = vec3(p.w, particles[id].optics.x * particles[id].optics.z, particles[id].optics.y);
    v_seen_tau = particles[id].optics.x * particles[id].optics.z / (widen * widen);
    v_floor_plane = particles[id].floor_plane.xyz;
    v_top_plane = particles[id].top_plane.xyz;
    v_fog = froxel_fog(corner_world);
    // The baked multiple scattering, read once a particle (particle_baked.comp).
#if LIGHT_VOLUME
    vec4 baked = u_lv_on != 0 ? baked_lights[id] : vec4(0.0);
#else
    vec4 baked = vec4(0.0);
#endif
    v_baked = baked.x;
    v_baked_slope = baked.yzw;
}
