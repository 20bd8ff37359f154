#version 450 core
// Blended with GL_MAX into one target: per pixel, minus the nearest and the farthest depth
// where the ray meets the shell (max(-a, -b) = -min(a, b), exactly).
in float v_depth;
layout(location = 0) out vec2 o_depths;
void main()
{
    o_depths = vec2(-v_depth, v_depth);
}
