#version 450 core
// The froxels' apply at a pixel whose samples see two surfaces (a ridge against the fogged
// valley behind it): the resolve averaged their colours and took the depth of one side
// (depth_resolve.frag: the side most samples lie on, the nearer on a tie), so one march at that
// depth would fog the other side's colour as if it lay there too, and a ridge's edge against a
// valley's fog would alias. Here, per pixel, the samples on the other side of the jump: their
// mean colour and their share of the samples (o_edge), their mean window depth (o_edge_depth;
// 1: the sky), and the pixel listed (FrameMarches) for its own march at that depth. Pixels
// of one surface get a share of 0. Two surfaces, and their split, as the resolve finds them
// (depth_samples.glsl).
layout(local_size_x = 8, local_size_y = 8) in;
uniform sampler2DMS u_ms_depth;
uniform sampler2DMS u_ms_color;
layout(rgba16f, binding = 0) writeonly uniform image2D o_edge;
layout(r32f, binding = 1) writeonly uniform image2D o_edge_depth;

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= u_size.x || px.y >= u_size.y)
        return;
    float lo, hi, centre;
    vec4 edge = vec4(0.0);
    float other_depth = 1.0;
    if (u_samples > 1 && ds_read(u_ms_depth, px, u_near_plane, u_far_plane, lo, hi, centre)) {
        float split = 0.5 * (lo + hi);
        bool resolved_near = texelFetch(u_depth, px, 0).r <= split;
        vec3 color = vec3(0.0);
        float count = 0.0, depth = 0.0;
        for (int s = 0; s < u_samples; ++s)
            if ((ds[s] <= split) != resolved_near) {
                color += texelFetch(u_ms_color, px, s).rgb;
                depth += ds[s];
                count += 1.0;
            }
        if (count > 0.0) {
            edge = vec4(color / count, count / float(u_samples));
            other_depth = depth / count;
            uint i = atomicAdd(fm_listed, 1u);
            if (i % 64u == 0u)
                atomicAdd(fm_dispatch.x, 1u);
            fm_pixels[i] = uint(px.x) | (uint(px.y) << 16);
        }
    }
    imageStore(o_edge, px, edge);
    imageStore(o_edge_depth, px, vec4(other_depth));
}
