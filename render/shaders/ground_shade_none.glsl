// Library: the fog's tau_sun at a fragment of the ground from its vertices alone, for a frame
// without a fine map of the fog's shade (ground_shade.glsl).
float ground_sun_depth(vec3 p, vec2 shade) { return shade.x; }
