// Library: no froxel fog in front of a surface (layers, particles) when the frame has none; the
// fog's program variant links froxel_common.glsl, froxel_medium.glsl and froxel_apply.glsl instead.
vec4 froxel_fog(vec3 world) { return vec4(0.0, 0.0, 0.0, 1.0); }
