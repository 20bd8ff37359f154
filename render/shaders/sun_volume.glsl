// Library (after medium_shell.glsl, froxel_medium.glsl and sun_march.glsl): tau_sun, the fog's
// optical depth towards the sun, as every renderer's lighting reads it (fog_lighting.glsl). In
// the Medium's shell, below its highest top, it is read from the sun volume (sun_volume.comp,
// built once per sun, fog and time: the Medium's part, marched), plus the height fog's in closed
// form at p (an exponential of a 25 m scale height is not linear between the shell's levels).
// Elsewhere, and without a volume (u_sv_on 0), the height fog's closed form and the Medium's part
// marched here in u_sv_steps steps (none above the Medium's highest top).
uniform int u_sv_on;
uniform sampler3D u_sv_volume;  // RG32F: the Medium's tau_sun per column and level (medium_shell.glsl), and 1
                                // where its path grazes the grid's edge (sun_path_grazes_a_wall)
uniform int u_sv_steps;

// Steps of the march where the volume cannot be read (below), at least.
const int sv_wall_steps = 48;

// Whether p's path towards the sun leaves the grid through a side wall near the fog's top or
// bottom there (or near a corner), within reach of a volume's neighbouring columns and levels
// (`size`: its columns and levels). The grid's edge is a vertical wall of fog: a path that leaves
// through it, below its top, holds fog in proportion to its length, and one that passes over it
// only what lies above; tau_sun kinks where the path grazes the wall's top, and read between
// columns on either side of that the volume's linear blend takes tens of per cent off it (an eye
// in fog at the grid's edge saw the whole frame 3.4 % too dark, docs/medium.md). The volume's
// fill marks its points where this holds (its second channel), and a lookup whose blend reaches
// a marked point marches the Medium instead.
bool sun_path_grazes_a_wall(vec3 p, vec3 s, vec3 size)
{
    vec2 lo = u_md_origin, hi = u_md_last;
    vec2 exits = (mix(lo, hi, greaterThan(s.xy, vec2(0.0))) - p.xy) / s.xy;  // s has no zero component
    int wall = exits.x < exits.y ? 0 : 1, along = 1 - wall;
    vec3 q = p + s * min(exits.x, exits.y);
    vec2 spacing = (hi - lo) / max(size.xy - 1.0, vec2(1.0));
    vec4 here = shell_column(p.xy), there = shell_column(q.xy);
    vec3 span = shell_span(here);
    // The height of q moves by this much as p moves to a neighbouring column or level.
    float inside = shell_inside(size.z);
    float level = p.z <= span.y ? (span.y - span.x) / (inside * (size.z - 1.0))
                                : (span.z - span.y) / ((1.0 - inside) * (size.z - 1.0));
    float margin = 1.25 * max(spacing[wall] * s.z / abs(s[wall]), level);
    if (!(q.z < u_md_ceiling + margin))
        return false;  // it leaves well over the fog's highest top
    bool corner = min(q[along] - lo[along], hi[along] - q[along]) < 1.5 * spacing[along];
    float top = there.z, bottom = max(there.x, there.y);
    return (corner && q.z < top + margin) || abs(q.z - top) < margin || abs(q.z - bottom) < margin;
}

// The Medium's part alone, with p's column (shell_column(p.xy), read where `covered`:
// shell_covers(p.xy)) at hand: the froxels' lit points and the layers' fragments have looked it up.
float medium_sun_optical_depth_in(vec3 p, vec3 s, float jitter, bool covered, vec4 column)
{
    if (!(u_md_on != 0 && p.z < u_md_ceiling))
        return 0.0;
    // One call of the march: each copy inlined costs llvmpipe compiling time and every lighting
    // pass's invocations a larger program (two took the default still's froxel lighting 12 %
    // longer).
    int steps = u_sv_steps;
    if (u_sv_on != 0 && covered) {
        vec2 tau_graze = shell_lookup_all_in(u_sv_volume, p, column).rg;
        if (!(tau_graze.y > 0.0))
            return max(tau_graze.x, 0.0);
        steps = max(steps, sv_wall_steps);
    }
    return medium_sun_depth(p, s, steps, jitter);
}

float medium_sun_optical_depth(vec3 p, vec3 s, float jitter)
{
    bool covered = u_sv_on != 0 && u_md_on != 0 && p.z < u_md_ceiling && shell_covers(p.xy);
    return medium_sun_optical_depth_in(p, s, jitter, covered, covered ? shell_column(p.xy) : vec4(0.0));
}

float sun_optical_depth_in(vec3 p, vec3 s, float jitter, bool covered, vec4 column)
{
    return medium_sun_optical_depth_in(p, s, jitter, covered, column) + height_fog_sun(p, s);
}

float sun_optical_depth(vec3 p, vec3 s, float jitter)
{
    return medium_sun_optical_depth(p, s, jitter) + height_fog_sun(p, s);
}
