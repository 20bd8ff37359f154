#version 450 core
// Puts the layers rendered at reduced resolution over the full-resolution frame. Depth-aware
// upsampling: of the four low-resolution texels around a pixel, those whose (terrain) depth
// matches the pixel's own weigh most, so fog does not bleed across ridge silhouettes. A pixel
// whose samples see two surfaces (a ridge against the fogged valley behind it, a thread of fog
// narrower than the pixel) takes the layers each sample's surface would have: the texels
// around each sample, matched to that sample's depth, averaged over the samples (the pixel's
// own texel holds the fog of one surface only, the one its resolved depth lies on). depth_samples.glsl
// gives the samples' count, offsets and depths (ds).
in vec2 v_ndc;
uniform sampler2D u_layers;     // premultiplied colour, low resolution
uniform sampler2D u_low_depth;  // the depth the layers were tested against
uniform sampler2D u_depth;      // full-resolution depth
uniform sampler2DMS u_samples_depth;  // the frame's samples' depth before the resolve
uniform bool u_at_samples;            // the layers drawn at the frame's resolution along each pixel's
                                      // samples' rays, each sample's blend apart (layers.frag's
uniform sampler2D u_layer_samples[3]; // LAYERS_AT_SAMPLES): samples 1..3's (u_layers holds sample 0's)
uniform vec2 u_low_size;
uniform float u_near;
uniform float u_far;
out vec4 o_color;

// The layers at image point uv (0..1) over a surface at view depth `depth`.
vec4 layers_at(vec2 uv, float depth)
{
    vec2 p = uv * u_low_size - 0.5;
    vec2 base = floor(p), f = p - base;
    vec4 sum = vec4(0.0);
    float weight = 0.0, best = 1e30;
    vec4 nearest = vec4(0.0);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            vec2 t = clamp(base + vec2(i, j), vec2(0.0), u_low_size - 1.0);
            vec2 tuv = (t + 0.5) / u_low_size;
            float d = view_depth(texture(u_low_depth, tuv).r, u_near, u_far);
            float gap = abs(d - depth) / max(depth, 1e-3);
            float g = gap / 0.01;  // 1 % of the distance halves the weight
            float w = (i == 1 ? f.x : 1.0 - f.x) * (j == 1 ? f.y : 1.0 - f.y) / (1.0 + g * g);
            vec4 c = texture(u_layers, tuv);
            sum += w * c;
            weight += w;
            if (gap < best) {
                best = gap;
                nearest = c;
            }
        }
    return weight > 1e-6 ? sum / weight : nearest;
}

// Reads pixel px's samples' depths into ds: whether they lie apart (the sky and the terrain, or
// depths more than 1 % apart: an edge, or ground seen at a grazing angle, where each sample's own
// texels serve it better too). At 5 % the lake's threads from afar (views bench) were 7.0 % off
// the reference, at 1 % 6.4 %; depth_samples.glsl's plane test too (a 3x3 solve a pixel) 6.5 %.
bool samples_apart(ivec2 px)
{
    float lo = 1.0, hi = 0.0;
    for (int s = 0; s < u_samples; ++s) {
        ds[s] = texelFetch(u_samples_depth, px, s).r;
        lo = min(lo, ds[s]);
        hi = max(hi, ds[s]);
    }
    return hi >= 1.0 ? lo < 1.0 : view_depth(hi, u_near, u_far) > 1.01 * view_depth(lo, u_near, u_far);
}

void main()
{
    vec2 uv = v_ndc * 0.5 + 0.5;
    ivec2 px = ivec2(gl_FragCoord.xy);
    if (u_at_samples) {
        vec4 c[8] = vec4[8](texelFetch(u_layers, px, 0), texelFetch(u_layer_samples[0], px, 0),
                            texelFetch(u_layer_samples[1], px, 0), texelFetch(u_layer_samples[2], px, 0), vec4(0.0),
                            vec4(0.0), vec4(0.0), vec4(0.0));
        // Each sample's own colour seen through its own blend of the stack (sample_blends.glsl).
        o_color = blends_over_samples(c, 4, px);
        return;
    }
    if (u_samples > 1 && samples_apart(px)) {
        vec2 size = vec2(textureSize(u_depth, 0));
        vec4 c[8] = vec4[8](vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0));
        for (int s = 0; s < ds_max && s < u_samples; ++s)
            c[s] = layers_at((vec2(px) + 0.5 + u_offsets[s]) / size, view_depth(ds[s], u_near, u_far));
        // Each sample's own colour seen through its own layers.
        o_color = blends_over_samples(c, u_samples, px);
        return;
    }
    o_color = layers_at(uv, view_depth(texture(u_depth, uv).r, u_near, u_far));
}
