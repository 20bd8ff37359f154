#version 450 core
// The shadow map low-passed as an exponential shadow map: a separable Gaussian of exp(k d)
// done in log space (log-sum-exp), so k can be large without overflow. Pass 0 reads the depth
// texture (light depth in [0, 1]) and blurs along x; pass 1 blurs its result along y.
layout(local_size_x = 8, local_size_y = 8) in;
layout(r32f, binding = 0) writeonly uniform image2D o_esm;
uniform sampler2D u_source;
uniform int u_pass;
uniform ivec2 u_size;
uniform float u_k_metres;  // k times the light depth range: depth [0, 1] -> k d in log space
uniform int u_radius;

float value(ivec2 p)
{
    p = clamp(p, ivec2(0), u_size - 1);
    float v = texelFetch(u_source, p, 0).r;
    return u_pass == 0 ? v * u_k_metres : v;
}

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= u_size.x || p.y >= u_size.y)
        return;
    ivec2 axis = u_pass == 0 ? ivec2(1, 0) : ivec2(0, 1);
    float top = -3e38;
    for (int i = -u_radius; i <= u_radius; ++i)
        top = max(top, value(p + axis * i));
    float sigma = max(0.5 * float(u_radius), 0.5), sum = 0.0, weights = 0.0;
    for (int i = -u_radius; i <= u_radius; ++i) {
        float w = exp(-0.5 * float(i * i) / (sigma * sigma));
        sum += w * exp(value(p + axis * i) - top);
        weights += w;
    }
    imageStore(o_esm, p, vec4(top + log(sum / weights), 0.0, 0.0, 0.0));
}
