#version 450 core
// Blended with GL_MIN into the first target and GL_MAX into the second: per pixel, the nearest
// and the farthest depth where the ray meets the shell.
in float v_depth;
layout(location = 0) out float o_first;
layout(location = 1) out float o_last;
void main()
{
    o_first = v_depth;
    o_last = v_depth;
}
