#version 450 core
// Depth alone (the froxel pass's low-resolution terrain depth, the sun's shadow map).
void main() {}
