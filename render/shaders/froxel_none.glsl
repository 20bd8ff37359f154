// Library: the terrain's shadow when the frame has no froxel fog (no shadow map): the plain
// terrain program carries none of terrain_shadow.glsl's cost (render/src/terrain_pass.cpp).
float terrain_shadow(vec3 world, vec3 n, vec3 sun) { return 1.0; }
