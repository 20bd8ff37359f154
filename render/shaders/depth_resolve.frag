#version 450 core
// The multisampled depth resolved to the pixel's centre, where every pass after the resolve
// (the froxels' apply, the particles' soft edge, the layers' upsampling, pick) takes it to lie.
// A copy of one sample (a blit) is that sample's depth: 4x MSAA puts sample 0 0.4 pixel off the
// centre, and over terrain seen at a grazing angle that is tens of metres nearer or farther.
// Where the samples lie on one plane (window depth is affine on a planar triangle) the plane
// fitted to them, read at the centre, is the centre's depth. Where they do not (an edge: the
// pixel straddles two surfaces), the plane through the samples on the side of the jump that most
// of them are on (the centre most likely lies with them), where those lie on one plane; else
// the nearest sample.
uniform sampler2DMS u_depth;
uniform int u_samples;      // at most 8
uniform vec2 u_offsets[8];  // each sample's offset from the pixel's centre (pixels)
uniform float u_near;       // the frame's projection
uniform float u_far;
out vec4 o_unused;

// Written in main before anything reads it; initialised so that Mesa's compiler, which cannot
// see that from plane_at_centre, does not warn of it on every start.
float d[8] = float[8](1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0);

float view_depth(float window)
{
    float z = window * 2.0 - 1.0;
    return 2.0 * u_near * u_far / (u_far + u_near - z * (u_far - u_near));
}

// The least-squares plane through the samples whose depth lies in [lo, hi], read at the centre
// (`at`), and whether they lie on it: at least three samples, none off it by more than 5 % of
// their spread.
bool plane_at_centre(float lo, float hi, out float at)
{
    mat3 normal = mat3(0.0);
    vec3 rhs = vec3(0.0);
    int count = 0;
    for (int s = 0; s < u_samples; ++s)
        if (d[s] >= lo && d[s] <= hi) {
            vec3 row = vec3(1.0, u_offsets[s]);
            normal += outerProduct(row, row);
            rhs += row * d[s];
            ++count;
        }
    at = lo;
    if (count < 3 || abs(determinant(normal)) < 1e-9)
        return false;
    vec3 plane = inverse(normal) * rhs;
    float residual = 0.0, low = 1.0, high = 0.0;
    for (int s = 0; s < u_samples; ++s)
        if (d[s] >= lo && d[s] <= hi) {
            residual = max(residual, abs(d[s] - dot(plane, vec3(1.0, u_offsets[s]))));
            low = min(low, d[s]);
            high = max(high, d[s]);
        }
    at = clamp(plane.x, low, high);
    return residual <= 0.05 * (high - low) + 4e-7;
}

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    float lo = 1.0, hi = 0.0;
    for (int s = 0; s < u_samples; ++s) {
        d[s] = texelFetch(u_depth, px, s).r;
        lo = min(lo, d[s]);
        hi = max(hi, d[s]);
    }
    float depth = lo;
    // Four samples cannot tell a jump split two and two across the diagonals from a steep plane:
    // a spread of more than a quarter of the nearest depth over less than a pixel is a jump.
    bool jump = hi < 1.0 ? view_depth(hi) > 1.25 * view_depth(lo) : lo < 1.0;
    if (u_samples < 3 || jump || !plane_at_centre(lo, hi, depth)) {
        depth = lo;
        float split = 0.5 * (lo + hi), near_count = 0.0;
        for (int s = 0; s < u_samples; ++s)
            near_count += d[s] <= split ? 1.0 : 0.0;
        float at;
        if (2.0 * near_count > float(u_samples)) {
            if (plane_at_centre(lo, split, at))
                depth = at;
        } else if (2.0 * near_count < float(u_samples)) {
            // The far side's plane: the sky (depth 1) where all its samples see the sky.
            if (plane_at_centre(split, hi, at))
                depth = at;
        }
    }
    gl_FragDepth = depth;
    o_unused = vec4(0.0);
}
