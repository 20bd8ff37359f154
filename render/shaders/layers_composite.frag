#version 450 core
// Puts the layers rendered at reduced resolution over the full-resolution frame. Depth-aware
// upsampling: of the four low-resolution texels around a pixel, those whose (terrain) depth
// matches the pixel's own weigh most, so fog does not bleed across ridge silhouettes.
in vec2 v_ndc;
uniform sampler2D u_layers;     // premultiplied colour, low resolution
uniform sampler2D u_low_depth;  // the depth the layers were tested against
uniform sampler2D u_depth;      // full-resolution depth
uniform vec2 u_low_size;
uniform float u_near;
uniform float u_far;
out vec4 o_color;

float linear_depth(float d)
{
    float z = d * 2.0 - 1.0;
    return 2.0 * u_near * u_far / (u_far + u_near - z * (u_far - u_near));
}

void main()
{
    vec2 uv = v_ndc * 0.5 + 0.5;
    float depth = linear_depth(texture(u_depth, uv).r);
    vec2 p = uv * u_low_size - 0.5;
    vec2 base = floor(p), f = p - base;
    vec4 sum = vec4(0.0);
    float weight = 0.0, best = 1e30;
    vec4 nearest = vec4(0.0);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            vec2 t = clamp(base + vec2(i, j), vec2(0.0), u_low_size - 1.0);
            vec2 tuv = (t + 0.5) / u_low_size;
            float d = linear_depth(texture(u_low_depth, tuv).r);
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
    o_color = weight > 1e-6 ? sum / weight : nearest;
}
