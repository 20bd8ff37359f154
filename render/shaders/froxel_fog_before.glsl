// Library (the split pixels' programs: froxel_edges.comp, froxel_pixels.comp): fog_before, the
// fog a ray through screen point uv crosses just before its surface at view depth `depth`. The
// Medium's column where the ray, followed back from the surface, is over the grid (at the
// surface, or where it crossed the grid's edge on its way to a surface beyond) is taken as
// level: the ray's length under its top within the grid (returned with the stretch beyond the
// grid, in view depth), what that and the height fog let through (t), where the ray meets the
// top of that fog, its skin, whose light is most of a dense fog's, with the share of the view the
// fog takes (skin: the point, the share), and its extinction there (sigma, 1/m). Meant to tell
// the samples of one pixel apart and to bound each one's march, not to light them: the march
// does that. The grid's edge is a wall of fog: a sample on the ground beyond it saw the wall's
// fog, one just inside it only the wall's depth, not all the fog over its own column. The height
// fog's is its closed form from the eye to the surface: a surface seen at a slant through its
// extent's wall (the DEM's edge) lies in haze on one side of the wall and in none on the other,
// within one pixel.

// The pixel whose samples the caller estimates (froxel_edges.comp, fog_before_for_pixel; else
// none): where the column at a sample's surface holds no fog, the fog may still lie before it in
// other columns (a shore seen from afar beyond the lake its ray crossed: the dense lake's far
// shores, pixels one sample of which is in fog and the rest not, left unsplit), so the ray is
// probed at four points of the stretch the rays of the pixels around it spend in the Medium's
// shell, found once a pixel.
ivec2 fog_before_pixel = ivec2(-1);
vec2 fog_before_shell = vec2(3e38, 0.0);
bool fog_before_shell_known = false;

void fog_before_for_pixel(ivec2 px)
{
    fog_before_pixel = px;
    fog_before_shell_known = false;
}

// The stretch of view depths over which the rays of the pixels around fog_before_pixel
// (rasterised at their centres) are in the Medium's shell; (3e38, 0) where none is.
vec2 fog_before_pixels_shell()
{
    if (!fog_before_shell_known) {
        fog_before_shell = vec2(3e38, 0.0);
        for (int y = -1; y <= 1; ++y)
            for (int x = -1; x <= 1; ++x) {
                vec2 s = froxel_pixel_shell(clamp(fog_before_pixel + ivec2(x, y), ivec2(0), u_size - 1));
                if (s.y > s.x)
                    fog_before_shell = vec2(min(fog_before_shell.x, s.x), max(fog_before_shell.y, s.y));
            }
        fog_before_shell_known = true;
    }
    return fog_before_shell;
}

float fog_before_probed(vec3 ray, float depth, float haze, inout float t, inout vec4 skin, inout float sigma)
{
    if (fog_before_pixel.x < 0)
        return 0.0;
    vec2 shell = fog_before_pixels_shell();
    // The same points for every sample of the pixel (those before its surface): points spread
    // over each sample's own stretch told samples of the same fog apart.
    float a = max(shell.x, 0.0), b = shell.y;
    if (!(b > a) || !(depth > a))
        return 0.0;
    const int probes = 4;
    // Each probe in the fog stands for its share of the stretch, or for the ray's way across the
    // column's depth there if that is shorter: a thin blanket crossed at a slant is no longer for
    // a stretch of kilometres around it (read as the whole share, the dense lake 9.3 % p99
    // against 9.2 %).
    float share = (b - a) / float(probes) * length(ray), slope = max(abs(normalize(ray).z), 1e-3);
    float inside = 0.0, coverage = 0.0, first = -1.0, along = 0.0;
    for (int k = 0; k < probes; ++k) {
        float v = a + (float(k) + 0.5) / float(probes) * (b - a);
        if (!(v < depth))
            break;
        vec3 x = u_fx_eye + ray * v;
        if (!shell_covers(x.xy))
            continue;
        vec4 c = shell_column(x.xy);
        if (x.z < c.z && x.z > c.x && c.w > 0.0) {
            inside += 1.0;
            coverage += c.w;
            along += min(share, (c.z - c.x) / slope);
            first = first < 0.0 ? v : first;
        }
    }
    if (!(inside > 0.0))
        return 0.0;
    sigma = u_md_extinction * coverage / inside;
    float fog = sigma * along;
    t = exp(-fog - haze);
    float entry = max(first - 0.5 * (b - a) / float(probes), a);
    skin = vec4(u_fx_eye + ray * entry, 1.0 - exp(-fog));
    return depth - entry;
}

// fog_before where the column at the surface holds fog; else (`probe` true) what the height fog
// alone lets through (t), with its optical depth (`haze`), for fog_before_probed: a caller with
// several samples probes only those that need it (llvmpipe runs a branch's code whether any lane
// takes it or not, so each sample's call of fog_before ran the probes).
float fog_before_column(vec2 uv, float depth, out float t, out vec4 skin, out float sigma, out float haze,
                        out bool probe)
{
    vec3 ray = fx_ray(uv);
    vec3 p = u_fx_eye + ray * depth;
    haze = height_fog_segment(u_fx_eye, p);
    t = exp(-haze);
    skin = vec4(0.0);
    sigma = 0.0;
    probe = false;
    if (u_fx_shell == 0)
        return 0.0;
    float reach = length(ray) * depth;  // the eye's distance: the ray is no longer
    vec3 back = -normalize(ray);        // from the surface towards the eye
    float enter = 0.0, leave = reach;   // its stretch over the grid
    if (!line_over_rect(p, back, u_md_origin, u_md_last, enter, leave))
        return 0.0;
    vec3 q = p + back * enter;
    vec4 c = shell_column(q.xy);  // floor, bottom, top, coverage
    float over = c.z > c.x ? c.z - q.z : 0.0;
    if (!(over > 0.0) || !(c.w > 0.0)) {
        probe = true;
        return 0.0;
    }
    float along = min(over / max(back.z, 1e-3), leave - enter);
    sigma = u_md_extinction * c.w;
    float fog = sigma * along;
    t = exp(-fog - haze);
    skin = vec4(q + back * along, 1.0 - exp(-fog));
    return (enter + along) * depth / reach;
}

// fog_before_column alone: the split samples' marches bound their stretch by it
// (froxel_pixels.comp); the probes tell samples apart (froxel_edges.comp), and compiled into the
// marches' program they ran in every sample's invocation on llvmpipe without a pixel to probe.
float fog_before(vec2 uv, float depth, out float t, out vec4 skin, out float sigma)
{
    float haze;
    bool probe;
    return fog_before_column(uv, depth, t, skin, sigma, haze, probe);
}
