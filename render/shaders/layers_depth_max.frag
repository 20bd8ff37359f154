#version 450 core
// The terrain's depth the layers drawn at reduced resolution are tested against, per
// low-resolution texel: the farthest of the full-resolution pixels it covers where they lie at
// about one depth (within 1 % a pixel across the texel); where the texel straddles a
// silhouette, the pixel at its centre.
// - Against one of the pixels (a nearest blit), a thin fog over flat ground seen at a grazing
//   angle lost its lowest layers wherever that pixel lay nearer than the texel's centre:
//   stripes across the fog. The farthest lets them through.
// - Across a silhouette the farthest would let the fog behind a ridge into the texel, and the
//   composite would spread it over the ridge; the nearest would take the fog from the texel's
//   far pixels (both measured: 0.5 and 8 points more error at a quarter resolution). The
//   centre's depth is what the composite's depth-aware weights were made for.
uniform sampler2D u_depth;  // the resolved frame's depth, full resolution
uniform vec2 u_scale;       // low-resolution texels per full-resolution pixel, each in (0, 1]
uniform float u_near;
uniform float u_far;
// At the frame's resolution with each slab along its samples' rays (layers.frag's
// LAYERS_AT_SAMPLES): the farthest of the pixel's samples, so that a layer any of them sees
// beyond the others' ground is drawn (each sample ends its own slabs at its own ground).
uniform sampler2DMS u_samples_depth;
uniform int u_samples;  // > 1: so

void main()
{
    if (u_samples > 1) {
        float farthest = 0.0;
        for (int s = 0; s < 8 && s < u_samples; ++s)
            farthest = max(farthest, texelFetch(u_samples_depth, ivec2(gl_FragCoord.xy), s).r);
        gl_FragDepth = farthest;
        return;
    }
    ivec2 size = textureSize(u_depth, 0);
    ivec2 low = ivec2(gl_FragCoord.xy);
    ivec2 first = ivec2(floor(vec2(low) / u_scale));
    ivec2 last = min(ivec2(ceil(vec2(low + 1) / u_scale)) - 1, size - 1);
    float nearest = 1.0, farthest = 0.0;
    for (int y = first.y; y <= last.y; ++y)
        for (int x = first.x; x <= last.x; ++x) {
            float d = texelFetch(u_depth, ivec2(x, y), 0).r;
            nearest = min(nearest, d);
            farthest = max(farthest, d);
        }
    float a = view_depth(nearest, u_near, u_far), b = view_depth(farthest, u_near, u_far);
    float pixels = 1.0 / min(u_scale.x, u_scale.y);
    ivec2 centre = min(ivec2(floor((vec2(low) + 0.5) / u_scale)), size - 1);
    gl_FragDepth = b - a <= 0.01 * pixels * a ? farthest : texelFetch(u_depth, centre, 0).r;
}
