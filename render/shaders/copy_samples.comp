#version 450 core
// Every sample of the multisampled colour side by side (pixel x's samples at x * u_samples + s
// of its row), for Renderer::read_radiance_samples.
layout(local_size_x = 8, local_size_y = 8) in;
uniform sampler2DMS u_color;
uniform int u_samples;
uniform ivec2 u_size;
layout(rgba32f, binding = 0) writeonly uniform image2D o_samples;

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= u_size.x || px.y >= u_size.y)
        return;
    for (int s = 0; s < u_samples; ++s)
        imageStore(o_samples, ivec2(px.x * u_samples + s, px.y), texelFetch(u_color, px, s));
}
