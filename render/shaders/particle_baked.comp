#version 450 core
// The baked multiple scattering (light_volume.glsl) each billboard takes towards the eye, once a
// frame for the billboards drawn: at its particle's centre, and how it changes with height across
// the ball. A ball is 250 to 500 m across and the baked light falls towards the fog's floor and
// the terrain's shade within it: read at the centre alone, the billboards drew it flat (inside
// the descent's fog 21.5 % off the baked reference, from the ridge 4.7 %). Read at half the
// radius above and below the centre (one-sided where one of them lies outside the shell, which
// the volume does not cover), the slope is what particles.frag extrapolates to each fragment's
// lit point.
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Particles { GpuParticle particles[]; };
layout(std430, binding = 2) readonly buffer Order { uint order[]; };  // the billboards drawn
layout(std430, binding = 3) writeonly buffer BakedLights { vec4 baked_lights[]; };
uniform int u_count;  // billboards drawn
uniform vec3 u_eye;
uniform vec3 u_centre;  // the cloud's centre (positions are relative to it)
uniform float u_anisotropy;

void main()
{
    int k = int(gl_GlobalInvocationID.x);
    if (k >= u_count)
        return;
    uint i = order[k];
    vec4 p = particles[i].position_radius;
    vec3 centre = p.xyz + u_centre;
    vec3 to_eye = u_eye - centre;
    float d = length(to_eye);
    vec3 towards = d > 1e-6 ? to_eye / d : vec3(0.0, 0.0, 1.0);
    float at = lv_in_scattered_at(centre, towards, u_anisotropy, false);
    float h = 0.5 * p.w;
    float above = lv_in_scattered_at(centre + vec3(0.0, 0.0, h), towards, u_anisotropy, false);
    float below = lv_in_scattered_at(centre - vec3(0.0, 0.0, h), towards, u_anisotropy, false);
    float slope = above > 0.0 && below > 0.0 ? (above - below) / (2.0 * h)
        : above > 0.0                       ? (above - at) / h
        : below > 0.0                       ? (at - below) / h
                                            : 0.0;
    // Extrapolated no further than the light read: the range of the three.
    float lo = min(at, min(above > 0.0 ? above : at, below > 0.0 ? below : at));
    float hi = max(at, max(above, below));
    baked_lights[i] = at > 0.0 && h > 0.0 ? vec4(at, slope, lo, hi) : vec4(at, 0.0, at, at);
}
