// Library: the fog's tau_sun at a fragment of the ground. From its vertices (GroundShade's
// (the Medium's tau_sun, refine, the height fog's), interpolated), but from the fine map where
// the shade bends between the vertices (refine > 0 at any of the triangle's corners): a fog's
// shore crossing a 75 m cell within metres, interpolated, spilled its shade over the sunlit
// ground beside it (the wind view: 4.4 % off the reference, with the fine map 2.8 %).
uniform sampler2D u_gs_fine;  // tau_sun at u_gs_fine_scale samples a cell (linear filtering): the
                              // Medium's part (below 0 beyond its shade: ground_shade.comp), the height fog's
uniform vec2 u_gs_origin;     // the DEM's first sample (m)
uniform vec2 u_gs_spacing;    // its spacing (m)
uniform float u_gs_fine_scale;

// The Medium's part (below 0 beyond its shade: ground_shade.comp) and the height fog's.
vec2 ground_sun_depths(vec3 p, vec4 shade)
{
    if (!(shade.y > 0.0))
        return shade.xz;
    vec2 texel = (p.xy - u_gs_origin) / u_gs_spacing * u_gs_fine_scale + 0.5;
    return textureLod(u_gs_fine, texel / vec2(textureSize(u_gs_fine, 0)), 0.0).rg;
}
