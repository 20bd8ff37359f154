#version 450 core
// The fog each pixel of the last frame received (what the apply computes at its depth, the
// terrain's depth at the pixel's centre here: froxel_upsample.comp and froxel_pixels.comp ran
// over it into u_fog), with the view depth, in float, for tests and benchmarks against the
// reference.
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) writeonly uniform image2D o_fog;
layout(r32f, binding = 1) writeonly uniform image2D o_depth;  // view depth; -1 for sky
uniform sampler2D u_fog;

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= u_size.x || px.y >= u_size.y)
        return;
    float depth = frame_depth(px);
    imageStore(o_fog, px, texelFetch(u_fog, px, 0));
    imageStore(o_depth, px, vec4(depth >= 3e38 ? -1.0 : depth));
}
