#version 450 core
// Attenuation buffer, pass 2: a prefix sum down every column turns the deposits into the shadow
// cylinders (log Gamma = sum of log G over the particles up-sun), converted from fixed point and
// clamped (never -inf). Buffers, not images: plain loads and stores are the cheap path; the
// result is copied into the 3D texture by the GL (glTextureSubImage3D from this buffer), as
// floats, or with KIRI_HALF as half floats packed two columns to a word (no conversion there).
layout(local_size_x = 64) in;
layout(std430, binding = 1) readonly buffer Sums { int sums[]; };
#ifdef KIRI_HALF
layout(std430, binding = 2) writeonly buffer LogGamma { uint log_gamma[]; };
#else
layout(std430, binding = 2) writeonly buffer LogGamma { float log_gamma[]; };
#endif
uniform ivec3 u_size;
uniform float u_inverse_scale;

float value(int sum) { return max(float(sum) * u_inverse_scale, -80.0); }

void main()
{
    int layer = u_size.x * u_size.y;
#ifdef KIRI_HALF
    int pair = int(gl_GlobalInvocationID.x);  // columns 2 pair and 2 pair + 1 (u_size.x is even)
    if (pair * 2 >= layer)
        return;
    int column = pair * 2;
    ivec2 sum = ivec2(0);
    for (int k = 0; k < u_size.z; ++k) {
        sum += ivec2(sums[k * layer + column], sums[k * layer + column + 1]);
        log_gamma[(k * layer + column) / 2] = packHalf2x16(vec2(value(sum.x), value(sum.y)));
    }
#else
    int column = int(gl_GlobalInvocationID.x);
    if (column >= layer)
        return;
    int sum = 0;
    for (int k = 0; k < u_size.z; ++k) {
        sum += sums[k * layer + column];
        log_gamma[k * layer + column] = value(sum);
    }
#endif
}
