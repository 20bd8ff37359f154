// Library: the fog's tau_sun at a fragment of the ground from its vertices alone, for a frame
// without a fine map of the fog's shade (ground_shade.glsl): the Medium's part (below 0 beyond
// its shade) and the height fog's.
vec2 ground_sun_depths(vec3 p, vec4 shade) { return shade.xz; }
