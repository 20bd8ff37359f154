// Library (after medium_shell.glsl, froxel_medium.glsl and sun_march.glsl): tau_sun, the fog's
// optical depth towards the sun, as every renderer's lighting reads it (fog_lighting.glsl). In
// the Medium's shell, below its highest top, it is read from the sun volume (sun_volume.comp,
// built once per sun, fog and time: the Medium's part, marched), plus the height fog's in closed
// form at p (an exponential of a 25 m scale height is not linear between the shell's levels).
// Elsewhere, and without a volume (u_sv_on 0), the height fog's closed form and the Medium's part
// marched here in u_sv_steps steps (none above the Medium's highest top).
uniform int u_sv_on;
uniform sampler3D u_sv_volume;  // R32F: the Medium's tau_sun per column and level (medium_shell.glsl)
uniform int u_sv_steps;

// The Medium's part alone.
float medium_sun_optical_depth(vec3 p, vec3 s, float jitter)
{
    if (!(u_md_on != 0 && p.z < u_md_ceiling))
        return 0.0;
    if (u_sv_on != 0 && shell_covers(p.xy))
        return max(shell_lookup(u_sv_volume, p), 0.0);
    return medium_sun_depth(p, s, u_sv_steps, jitter);
}

float sun_optical_depth(vec3 p, vec3 s, float jitter)
{
    return medium_sun_optical_depth(p, s, jitter) + height_fog_sun(p, s);
}
