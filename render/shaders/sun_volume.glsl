// Library (after medium_shell.glsl, froxel_medium.glsl and sun_march.glsl): tau_sun, the fog's
// optical depth towards the sun, as every renderer's lighting reads it (fog_lighting.glsl): the
// Medium's part from the sun volume (sun_volume.comp, built once per sun, Medium and time), the
// height fog's part in closed form. Without a volume (u_sv_on 0) the Medium's part is marched
// here in u_sv_steps steps; outside the grid too, where the volume holds no columns.
uniform int u_sv_on;
uniform sampler3D u_sv_volume;  // R32F: the Medium's tau_sun per column and level (medium_shell.glsl)
uniform int u_sv_steps;

float sun_medium_depth(vec3 p, vec3 s, float jitter)
{
    if (u_md_on == 0 || p.z >= u_md_ceiling)
        return 0.0;  // no fog above the Medium's highest top
    if (u_sv_on != 0 && shell_covers(p.xy))
        return max(shell_lookup(u_sv_volume, p), 0.0);
    return medium_sun_depth(p, s, u_sv_steps, jitter);
}

float sun_optical_depth(vec3 p, vec3 s, float jitter) { return height_fog_sun(p, s) + sun_medium_depth(p, s, jitter); }
