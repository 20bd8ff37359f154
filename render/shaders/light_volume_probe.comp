#version 450 core
// lv_in_scattered (light_volume.glsl) at given points, read back: what the renderers' baked
// multiple scattering takes there, for the tests against geometry::LightVolume::in_scattered; with
// a height (z_parts.y 1), its part on that height's side of the terrain's shadow (in_scattered_at).
layout(local_size_x = 64) in;
struct Probe {
    vec4 xyh_scale;
    vec4 towards_g;
    vec4 z_parts;  // the point's height, 1: take its part
};
layout(std430, binding = 0) readonly buffer Points { Probe points[]; };
layout(std430, binding = 1) writeonly buffer Values { float values[]; };
uniform int u_count;

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i < u_count) {
        Probe p = points[i];
        int part = p.z_parts.y > 0.5 && u_lv_parts_group >= 0
            ? (p.z_parts.x < lv_shadow_top_at(p.xyh_scale.xy) ? 1 : 0)
            : -1;
        values[i] = lv_in_scattered_part(p.xyh_scale.xy, p.xyh_scale.z, p.xyh_scale.w, p.towards_g.xyz, p.towards_g.w,
                                         part);
    }
}
