// Library: the points of the apply's grids of samples (froxel_pixels.comp,
// froxel_upsample.comp) as a finer grid's points judge them. Needs froxel_march.glsl (the
// shell's per-pixel depths) and froxel_frame.glsl before it.

// How deep the Medium's fog lies over pixel px's surface (0: the sky, or none there). A thread of
// fog in a valley narrower than the samples' spacing, seen from afar between two ridges without
// fog, shows here: the shell's blocks are too coarse to show it in its depths.
float fog_over_surface(ivec2 px, float depth)
{
    if (!(depth < 3e38))
        return 0.0;
    vec3 p = fx_world(frame_uv(px), depth);
    if (!shell_covers(p.xy))
        return 0.0;
    vec4 c = shell_column(p.xy);  // floor, bottom, top, coverage
    return c.z > c.x ? max(c.z - p.z, 0.0) : 0.0;
}

// What a finer grid's points judge a point of this grid by (froxel_upsampled), kept with it:
// its surface's depth, the fog over its surface, its stretch of the shell (entry and exit; 0
// without the shell's depths). Read from there, a pixel between four points reads one texel of
// each instead of their depths, shell and columns.
vec4 frame_point_info(ivec2 px, float depth)
{
    vec2 shell = u_fx_shell != 0 ? froxel_pixel_shell(px) : vec2(0.0);
    return vec4(depth, fog_over_surface(px, depth), shell);
}
