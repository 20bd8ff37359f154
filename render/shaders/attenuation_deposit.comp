#version 450 core
// Attenuation buffer, pass 1 (light_grid.hpp, attenuation_cpu.hpp): every particle adds log G of
// its footprint to the first voxel of its shadow cylinder in each column it covers. Fixed point
// with integer atomics on a buffer: the sums are exact, so the order of the particles (and of the
// threads) cannot change the result.
//
// Two layouts. 32 bits a voxel: -log G in units of 1 / u_scale. KIRI_PACKED: two neighbouring
// columns share a 32-bit word, 16 bits each, holding |log G| in units of 1 / u_scale; the CPU
// picked u_scale so that no voxel's sum can pass 65535 (no carry into the other half), and one
// atomic writes both columns: on a CPU rasteriser every atomic is a scalar loop over the SIMD
// lanes, so this halves the pass's memory operations.
//
// The rest is cost per column too: the Gaussian exp(-(a dx^2 + b dy^2)) is separable, so it is
// one exp per row and a running product along it (E_(i+1) = E_i R_i, R_(i+1) = R_i Q);
// log G = log(1 - b (1 - exp(-t))), b = 1 - ac, t = tau f, is its Taylor polynomial in t for thin
// particles (tau <= 0.1: the first term left out is below 1e-6 of the value) and exp + log
// otherwise (absolute error ~1e-7 in float, below the fixed point's step). The particles come
// sorted by footprint size, so the lanes of a SIMD batch loop alike.
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Particles { GpuParticle particles[]; };
#ifdef KIRI_PACKED
layout(std430, binding = 1) buffer Sums { uint sums[]; };  // columns (2m, 2m + 1) of a row at ((k ny + j) nx) / 2 + m
#else
layout(std430, binding = 1) buffer Sums { int sums[]; };  // voxel (i, j, k) at (k ny + j) nx + i
#endif
uniform uint u_count;
uniform float u_scale;

void main()
{
    uint id = gl_GlobalInvocationID.x;
    if (id >= u_count)
        return;
    GpuParticle particle = particles[id];
    // tau with the mass cut off by the ground and the fog's floor and top given back (seen_gain);
    // a ball such a plane cuts has each column cut too (column_plane_share).
    float r = particle.position_radius.w, tau = particle.optics.x * particle.optics.z;
    if (!(r > 0.0) || !(tau > 0.0))
        return;
    Ball ball = ball_of(particle);
    bool cut = planes_cut(ball);
    float ac = clamp(particle.optics.y, 0.0, 1.0) * clamp(u_forward, 0.0, 1.0);
    vec3 g = grid_of(particle.position_radius.xyz);
    vec4 p_grid = vec4(g, shadow_grid(g).z);  // gx, gy, gz, gw0
    float e0 = exp(-1.0 / (2.0 * kFootprintSigma * kFootprintSigma));
    // Rows whose centre lies within r of the axis; in each, the columns within the chord.
    vec2 reach = vec2(r) / u_grid_voxel.xy;
    int j0 = max(0, int(ceil(p_grid.y - reach.y - 0.5))), j1 = min(u_grid_size.y - 1, int(floor(p_grid.y + reach.y - 0.5)));
    vec2 alpha = u_grid_voxel.xy * u_grid_voxel.xy / (2.0 * kFootprintSigma * kFootprintSigma * r * r);
    float q = exp(-2.0 * alpha.x);
    // log(1 - b (1 - e^-t)) = c1 t + c2 t^2 + c3 t^3 + c4 t^4 + O(t^5), times the scale.
    float b = 1.0 - ac;
    bool thin = tau <= 0.1;
    vec4 taylor = u_scale * vec4(-b, 0.5 * b * (1.0 - b), -b / 6.0 + 0.5 * b * b - b * b * b / 3.0,
                                 b / 24.0 - 7.0 * b * b / 24.0 + 0.5 * b * b * b - 0.25 * b * b * b * b);
    // t = tau f = max(A e - B, 0).
    float A = tau / (1.0 - e0), B = tau * e0 / (1.0 - e0);
    int layer = u_grid_size.x * u_grid_size.y;
    for (int j = j0; j <= j1; ++j) {
        float dy = float(j) + 0.5 - p_grid.y;
        float chord = sqrt(max(reach.x * reach.x * (1.0 - dy * dy / (reach.y * reach.y)), 0.0));
        int a = max(0, int(ceil(p_grid.x - chord - 0.5))), z = min(u_grid_size.x - 1, int(floor(p_grid.x + chord - 0.5)));
#ifdef KIRI_PACKED
        a &= ~1;  // whole pairs: a column outside the chord gets f = 0 below, nothing
#endif
        float xa = float(a) + 0.5 - p_grid.x;
        float e = exp(-alpha.x * xa * xa - alpha.y * dy * dy), step = exp(-alpha.x * (2.0 * xa + 1.0));
        // Shadow start along the row: gw0 - a' (i + 0.5) - b' (j + 0.5) - 0.5, stepping by -a'.
        float start = p_grid.w - u_grid_shear_cells.y * (float(j) + 0.5) - u_grid_shear_cells.x * (float(a) + 0.5) - 0.5;
        int row = j * u_grid_size.x;
#ifdef KIRI_PACKED
        for (int i = a; i <= z; i += 2) {
            float t0 = max(A * e - B, 0.0);
            e *= step;
            step *= q;
            float t1 = i + 1 <= z ? max(A * e - B, 0.0) : 0.0;
            e *= step;
            step *= q;
            if (cut) {
                vec2 offset = vec2((float(i) + 0.5 - p_grid.x) * u_grid_voxel.x, dy * u_grid_voxel.y);
                t0 *= column_plane_share(offset, ball);
                t1 *= column_plane_share(offset + vec2(u_grid_voxel.x, 0.0), ball);
            }
            float k0 = ceil(start), k1 = ceil(start - u_grid_shear_cells.x);
            start -= 2.0 * u_grid_shear_cells.x;
            vec2 t = vec2(t0, t1);
            vec2 fixed_g = thin ? t * (taylor.x + t * (taylor.y + t * (taylor.z + t * taylor.w)))
                                : clamp(log(ac + b * exp(-t)), kMinLogGain, 0.0) * u_scale;
            uvec2 m = uvec2(floor(-fixed_g + 0.5));  // magnitudes, >= 0
            int word = (row + i) / 2;
            if (k0 == k1) {
                if (k0 < float(u_grid_size.z) && (m.x | m.y) != 0u)
                    atomicAdd(sums[max(int(k0), 0) * (layer / 2) + word], m.x | (m.y << 16));
            } else {  // a sheared slice boundary between the two: one atomic each
                if (k0 < float(u_grid_size.z) && m.x != 0u)
                    atomicAdd(sums[max(int(k0), 0) * (layer / 2) + word], m.x);
                if (k1 < float(u_grid_size.z) && m.y != 0u)
                    atomicAdd(sums[max(int(k1), 0) * (layer / 2) + word], m.y << 16);
            }
        }
#else
        for (int i = a; i <= z; ++i, e *= step, step *= q, start -= u_grid_shear_cells.x) {
            float k = ceil(start);
            if (k >= float(u_grid_size.z))
                continue;
            float t = max(A * e - B, 0.0);
            if (cut)
                t *= column_plane_share(vec2((float(i) + 0.5 - p_grid.x) * u_grid_voxel.x, dy * u_grid_voxel.y), ball);
            float fixed_g = thin ? t * (taylor.x + t * (taylor.y + t * (taylor.z + t * taylor.w)))
                                 : clamp(log(ac + b * exp(-t)), kMinLogGain, 0.0) * u_scale;
            int quantum = int(floor(fixed_g + 0.5));
            if (quantum != 0)
                atomicAdd(sums[max(int(k), 0) * layer + row + i], quantum);
        }
#endif
    }
}
