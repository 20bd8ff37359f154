// Library: a pixel's samples' blends (premultiplied colour and coverage, one a sample: a still
// drawn at each sample, or fog taken at each sample's own surface) put over the frame as one.
// Where the frame below is still the mean of its samples (nothing blended into it since the
// resolve), each sample's own colour is seen through its own blend: mean((1 - a_s) b_s), where
// blending the mean over the frame gives (1 - mean a) mean b.
uniform sampler2DMS u_samples_color;  // the frame's samples' colour, when the frame below is their mean
uniform bool u_samples_below;         // (nothing blended into it since the resolve)

// What to blend over the frame at pixel px for its first n (at most 8) samples' blends c.
vec4 blends_over_samples(vec4 c[8], int n, ivec2 px)
{
    vec4 sum = vec4(0.0);
    vec3 through = vec3(0.0), below = vec3(0.0);
    for (int s = 0; s < 8 && s < n; ++s) {
        sum += c[s];
        if (u_samples_below) {
            vec3 b = texelFetch(u_samples_color, px, s).rgb;
            through += (1.0 - c[s].a) * b;
            below += b;
        }
    }
    vec4 over = sum / float(n);
    if (u_samples_below)
        over.rgb += (through - (1.0 - over.a) * below) / float(n);
    return over;
}
