// Library (after medium_shell.glsl and froxel_medium.glsl): the Medium's optical depth from p
// towards the sun s (unit), marched in `steps` steps to the exit of its box, each step's sample
// at `jitter` in [0, 1) of it. The height fog's part is height_fog_sun's closed form.
uniform vec3 u_box_min;  // the Medium's bounds
uniform vec3 u_box_max;

float medium_sun_depth(vec3 p, vec3 s, int steps, float jitter)
{
    if (u_md_on == 0)
        return 0.0;
    // Exit of the Medium's box along the sun (slab test).
    vec3 inv = 1.0 / s;
    vec3 a = (u_box_min - p) * inv, b = (u_box_max - p) * inv;
    vec3 far_t = max(a, b), near_t = min(a, b);
    float t0 = max(max(near_t.x, near_t.y), max(near_t.z, 0.0));
    float t1 = min(min(far_t.x, far_t.y), far_t.z);
    if (!(t1 > t0))
        return 0.0;
    // Half the steps evenly up to twice where the sun leaves the fog's top above p (the grid's
    // top there): in a dense fog nearly all of tau_sun lies there, and with the scattering
    // octaves (exp(-tau / 4)) its error shows. The rest grow quadratically to the box's exit,
    // for fog the sun crosses farther away.
    float split = t0;
    if (s.z > 1e-3 && shell_covers(p.xy)) {
        vec4 c = shell_column(p.xy);  // floor, bottom, top, coverage
        if (c.w > 0.0 && p.z < c.z)
            split = clamp(t0 + 2.0 * (c.z - max(p.z, c.y)) / s.z, t0, t1);
    }
    int near_steps = split > t0 ? max(steps / 2, 1) : 0, far_steps = max(steps - near_steps, 1);
    // Both runs in one loop: one copy of the density's lookup for the compiler to inline.
    float tau = 0.0, n = float(far_steps);
    for (int k = 0; k < near_steps + far_steps; ++k) {
        float s0, s1;
        if (k < near_steps) {
            s0 = mix(t0, split, float(k) / float(near_steps));
            s1 = mix(t0, split, float(k + 1) / float(near_steps));
        } else {
            float u0 = float(k - near_steps) / n, u1 = float(k - near_steps + 1) / n;
            s0 = split + (t1 - split) * u0 * u0;
            s1 = split + (t1 - split) * u1 * u1;
        }
        tau += medium_sigma(p + s * mix(s0, s1, jitter)) * (s1 - s0);
    }
    return tau;
}
