#version 450 core
// The multisampled depth resolved to the pixel's centre, where every pass after the resolve
// (the froxels' apply, the particles' soft edge, the layers' upsampling, pick) takes it to lie.
// A copy of one sample (a blit) is that sample's depth: 4x MSAA puts sample 0 0.4 pixel off the
// centre, and over terrain seen at a grazing angle that is tens of metres nearer or farther.
// Where the samples lie on one plane (window depth is affine on a planar triangle) the plane
// fitted to them, read at the centre, is the centre's depth; where they do not (an edge: the
// pixel straddles two surfaces), the nearest sample, as the surface in front hides what lies
// behind it.
uniform sampler2DMS u_depth;
uniform int u_samples;             // at most 8
uniform vec2 u_offsets[8];         // each sample's offset from the pixel's centre (pixels)
uniform vec4 u_fit[3 * 2];         // (a, b, c) = F d: the least-squares plane's rows, 8 samples as two vec4
out vec4 o_unused;

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    float d[8];
    float lo = 1.0, hi = 0.0;
    for (int s = 0; s < 8; ++s) {
        d[s] = s < u_samples ? texelFetch(u_depth, px, s).r : 0.0;
        if (s < u_samples) {
            lo = min(lo, d[s]);
            hi = max(hi, d[s]);
        }
    }
    vec4 d0 = vec4(d[0], d[1], d[2], d[3]), d1 = vec4(d[4], d[5], d[6], d[7]);
    float a = dot(u_fit[0], d0) + dot(u_fit[1], d1);
    float b = dot(u_fit[2], d0) + dot(u_fit[3], d1);
    float c = dot(u_fit[4], d0) + dot(u_fit[5], d1);
    float residual = 0.0;
    for (int s = 0; s < u_samples; ++s)
        residual = max(residual, abs(d[s] - (a + b * u_offsets[s].x + c * u_offsets[s].y)));
    bool planar = residual <= 0.05 * (hi - lo) + 4e-7;
    gl_FragDepth = planar ? clamp(a, lo, hi) : lo;
    o_unused = vec4(0.0);
}
