#version 450 core
// The multisampled depth resolved to the pixel's centre, where every pass after the resolve
// (the froxels' apply, the particles' soft edge, the layers' upsampling, pick) takes it to lie.
// A copy of one sample (a blit) is that sample's depth: 4x MSAA puts sample 0 0.4 pixel off the
// centre, and over terrain seen at a grazing angle that is tens of metres nearer or farther.
// Where the samples lie on one plane (window depth is affine on a planar triangle) the plane
// fitted to them, read at the centre, is the centre's depth. Where they do not (an edge: the
// pixel straddles two surfaces, depth_samples.glsl), the plane through the samples on the side
// of the jump that most of them are on (the centre most likely lies with them), where those lie
// on one plane; else the nearest sample.
uniform sampler2DMS u_depth;
uniform float u_near;  // the frame's projection
uniform float u_far;
out vec4 o_unused;

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    float lo, hi, depth;
    if (ds_read(u_depth, px, u_near, u_far, lo, hi, depth)) {
        depth = lo;
        float split = 0.5 * (lo + hi), near_count = 0.0;
        for (int s = 0; s < ds_max && s < u_samples; ++s)
            near_count += ds[s] <= split ? 1.0 : 0.0;
        float at;
        if (2.0 * near_count > float(u_samples)) {
            if (ds_plane_at_centre(lo, split, at))
                depth = at;
        } else if (2.0 * near_count < float(u_samples)) {
            // The far side's plane: the sky (depth 1) where all its samples see the sky.
            if (ds_plane_at_centre(split, hi, at))
                depth = at;
        }
    }
    gl_FragDepth = depth;
    o_unused = vec4(0.0);
}
