// Library (the split pixels' programs: froxel_edges.comp, froxel_pixels.comp). The fog a ray through screen point uv crosses just before its surface at view depth `depth`:
// the Medium's column where the ray, followed back from the surface, is over the grid (at the
// surface, or where it crossed the grid's edge on its way to a surface beyond) taken as level,
// the ray's length under its top within the grid (returned with the stretch beyond the grid, in
// view depth), what that and the height fog let through (t), and where the ray meets the top of
// the Medium's fog, its skin, whose light is most of a dense fog's, with the share of the view
// that fog takes (skin: the point, the share), and its extinction there (sigma, 1/m). Meant
// to tell the samples of one pixel apart and to bound each one's march, not to light them: the
// march does that. The grid's edge is a wall of fog: a
// sample on the ground beyond it saw the wall's fog, one just inside it only the wall's depth,
// not all the fog over its own column. The height fog's is its closed form from the eye to the
// surface: a surface seen at a slant through its extent's wall (the DEM's edge) lies in haze on
// one side of the wall and in none on the other, within one pixel.
float fog_before(vec2 uv, float depth, out float t, out vec4 skin, out float sigma)
{
    vec3 ray = fx_ray(uv);
    vec3 p = u_fx_eye + ray * depth;
    float haze = height_fog_segment(u_fx_eye, p);
    t = exp(-haze);
    skin = vec4(0.0);
    sigma = 0.0;
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
    if (!(over > 0.0) || !(c.w > 0.0))
        return 0.0;
    float along = min(over / max(back.z, 1e-3), leave - enter);
    sigma = u_md_extinction * c.w;
    float fog = sigma * along;
    t = exp(-fog - haze);
    skin = vec4(q + back * along, 1.0 - exp(-fog));
    return (enter + along) * depth / reach;
}
