// Library (before froxel_medium.glsl): the Medium's grid (geometry::MediumGrid) and the shell
// coordinates of a volume that follows it, for the passes that store something per point of the
// fog (the sun's optical depth, sun_volume.glsl) instead of evaluating it per pixel.
//
// A shell volume has nx x ny columns spread evenly over the grid's samples, from the first
// (u_md_origin) to the last (u_md_last): with as many columns as the grid has samples, the
// columns are the samples. A column's levels follow its height: about 60 % of them
// (shell_inside) run evenly from the column's floor (nothing lies below it) to its top, the rest
// from the top to the ceiling, the Medium's highest top, above which there is no fog. So a thin
// fog in a valley gets as many levels as a deep one, and the fog of a higher neighbour that the
// sun crosses on its way is still held above a low column's top. The top is a level: the sun's
// optical depth kinks there (none above, growing below), and a lookup between levels on either
// side of it put a dense fog's sunlit skin in the dark (at 1 per metre, tau_sun 3.5 at the top).
uniform sampler2D u_md_grid;  // RGBA32F: floor, bottom, top, coverage per grid sample (linear, clamp)
uniform vec2 u_md_origin;     // grid sample (0, 0)
uniform vec2 u_md_last;       // grid sample (nx - 1, ny - 1)
uniform vec2 u_md_cells;      // nx, ny
uniform float u_md_ceiling;   // the Medium's highest top (m)

// The share of a volume's `levels` levels from a column's floor to its top (the top a level).
float shell_inside(float levels)
{
    float intervals = max(levels - 1.0, 1.0);
    return clamp(round(0.6 * intervals), 1.0, max(intervals - 1.0, 1.0)) / intervals;
}

// Where (x, y) lies over the grid: 0 at the first sample, 1 at the last.
vec2 shell_fraction(vec2 xy) { return (xy - u_md_origin) / (u_md_last - u_md_origin); }

bool shell_covers(vec2 xy)
{
    vec2 f = shell_fraction(xy);
    return all(greaterThanEqual(f, vec2(0.0))) && all(lessThanEqual(f, vec2(1.0)));
}

// The grids at (x, y), bilinear between the samples: floor, bottom, top, coverage.
vec4 shell_column(vec2 xy)
{
    vec2 st = (shell_fraction(xy) * (u_md_cells - 1.0) + 0.5) / u_md_cells;
    return textureLod(u_md_grid, st, 0.0);
}

// The heights a column's levels span: its floor, its top (at least 1 m above the floor) and the
// ceiling (at least 1 m above that).
vec3 shell_span(vec4 column)
{
    float z0 = column.x, z1 = max(column.z, z0 + 1.0);
    return vec3(z0, z1, max(u_md_ceiling, z1 + 1.0));
}

// The level coordinate w in [0, 1] of height z in a column (clamped below its floor and above the
// ceiling) in a volume of `levels` levels, and its inverse.
float shell_level(float z, vec4 column, float levels)
{
    vec3 s = shell_span(column);
    float inside = shell_inside(levels);
    float w = z <= s.y ? inside * (z - s.x) / (s.y - s.x) : inside + (1.0 - inside) * (z - s.y) / (s.z - s.y);
    return clamp(w, 0.0, 1.0);
}

float shell_height(float w, vec4 column, float levels)
{
    vec3 s = shell_span(column);
    float inside = shell_inside(levels);
    return w <= inside ? mix(s.x, s.y, w / inside) : mix(s.y, s.z, (w - inside) / (1.0 - inside));
}

// The position of column (i, j) of a volume of `columns` columns.
vec2 shell_column_xy(ivec2 ij, ivec2 columns)
{
    return mix(u_md_origin, u_md_last, vec2(ij) / vec2(max(columns - 1, ivec2(1))));
}

// The value of a shell volume (one channel) at p: one trilinear lookup at p's level in its own
// column (the grids bilinear at p, as the volume's columns took them at theirs). A quantity that
// varies linearly with the level between a column's floor and top, such as the optical depth
// under a flat top, blends exactly between columns whose floors differ. Outside the grid: the
// nearest columns.
// shell_lookup_all_in: with p's column (shell_column(p.xy)) already at hand.
vec4 shell_lookup_all_in(sampler3D volume, vec3 p, vec4 column)
{
    vec3 size = vec3(textureSize(volume, 0));
    vec2 f = clamp(shell_fraction(p.xy), 0.0, 1.0);
    float w = shell_level(p.z, column, size.z);
    return textureLod(volume, (vec3(f, w) * (size - 1.0) + 0.5) / size, 0.0);
}
vec4 shell_lookup_all(sampler3D volume, vec3 p) { return shell_lookup_all_in(volume, p, shell_column(p.xy)); }

float shell_lookup(sampler3D volume, vec3 p) { return shell_lookup_all(volume, p).r; }
