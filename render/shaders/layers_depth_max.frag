#version 450 core
// The terrain's depth the layers drawn at reduced resolution are tested against: the farthest
// of the full-resolution pixels each low-resolution texel covers. Against one of them (a
// nearest blit) a thin fog over flat ground seen at a grazing angle lost its lowest layers
// wherever that pixel lay nearer than the texel's centre: stripes across the fog. Where a
// texel straddles a silhouette, the composite's depth-aware weights keep the fog behind it off
// the nearer surface.
uniform sampler2D u_depth;  // the resolved frame's depth, full resolution
uniform vec2 u_scale;       // low-resolution texels per full-resolution pixel, each in (0, 1]

void main()
{
    ivec2 size = textureSize(u_depth, 0);
    ivec2 low = ivec2(gl_FragCoord.xy);
    ivec2 first = ivec2(floor(vec2(low) / u_scale));
    ivec2 last = min(ivec2(ceil(vec2(low + 1) / u_scale)) - 1, size - 1);
    float farthest = 0.0;
    for (int y = first.y; y <= last.y; ++y)
        for (int x = first.x; x <= last.x; ++x)
            farthest = max(farthest, texelFetch(u_depth, ivec2(x, y), 0).r);
    gl_FragDepth = farthest;
}
