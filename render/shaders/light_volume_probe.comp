#version 450 core
// lv_in_scattered (light_volume.glsl) at given points, read back: what the renderers' baked
// multiple scattering takes there, for the tests against geometry::LightVolume::in_scattered.
layout(local_size_x = 64) in;
struct Probe {
    vec4 xyh_scale;
    vec4 towards_g;
};
layout(std430, binding = 0) readonly buffer Points { Probe points[]; };
layout(std430, binding = 1) writeonly buffer Values { float values[]; };
uniform int u_count;

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i < u_count) {
        Probe p = points[i];
        values[i] = lv_in_scattered(p.xyh_scale.xy, p.xyh_scale.z, p.xyh_scale.w, p.towards_g.xyz, p.towards_g.w);
    }
}
