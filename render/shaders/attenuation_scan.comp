#version 450 core
// Attenuation buffer, pass 2: a prefix sum down every column turns the deposits into the shadow
// cylinders (log Gamma = sum of log G over the particles up-sun), converted from fixed point and
// clamped (never -inf). Buffers, not images, and four adjacent columns per invocation
// (KIRI_QUAD, widths divisible by 4): one 16-byte load and one store per step instead of four of
// each. The result is copied into the 3D texture by the GL (glTextureSubImage3D from this
// buffer), as floats, or with KIRI_HALF as half floats packed by this pass (no conversion there).
// KIRI_PACKED reads the deposit's packed layout (two 16-bit magnitudes a word; u_inverse_scale
// then carries the minus sign).
layout(local_size_x = 64) in;
#if defined(KIRI_PACKED)
layout(std430, binding = 1) readonly buffer Sums { uvec2 sums[]; };
ivec4 load(int index)
{
    uvec2 w = sums[index];
    return ivec4(uvec4(w.x & 0xFFFFu, w.x >> 16, w.y & 0xFFFFu, w.y >> 16));
}
#elif defined(KIRI_QUAD)
layout(std430, binding = 1) readonly buffer Sums { ivec4 sums[]; };
ivec4 load(int index) { return sums[index]; }
#else
layout(std430, binding = 1) readonly buffer Sums { int sums[]; };
#endif
#ifdef KIRI_QUAD
#ifdef KIRI_HALF
layout(std430, binding = 2) writeonly buffer LogGamma { uvec2 log_gamma[]; };
#else
layout(std430, binding = 2) writeonly buffer LogGamma { vec4 log_gamma[]; };
#endif
#else
layout(std430, binding = 2) writeonly buffer LogGamma { float log_gamma[]; };
#endif
uniform ivec3 u_size;
uniform float u_inverse_scale;

void main()
{
    int layer = u_size.x * u_size.y;
#ifdef KIRI_QUAD
    int quad = int(gl_GlobalInvocationID.x), quads = layer / 4;
    if (quad >= quads)
        return;
    ivec4 sum = ivec4(0);
    for (int k = 0; k < u_size.z; ++k) {
        sum += load(k * quads + quad);
        vec4 v = max(vec4(sum) * u_inverse_scale, vec4(-80.0));
#ifdef KIRI_HALF
        log_gamma[k * quads + quad] = uvec2(packHalf2x16(v.xy), packHalf2x16(v.zw));
#else
        log_gamma[k * quads + quad] = v;
#endif
    }
#else
    int column = int(gl_GlobalInvocationID.x);
    if (column >= layer)
        return;
    int sum = 0;
    for (int k = 0; k < u_size.z; ++k) {
        sum += sums[k * layer + column];
        log_gamma[k * layer + column] = max(float(sum) * u_inverse_scale, -80.0);
    }
#endif
}
