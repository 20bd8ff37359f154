#version 450 core
// Attenuation buffer, pass 1 (light_grid.hpp, attenuation_cpu.hpp): every particle adds log G of
// its footprint to the first voxel of its shadow cylinder in each column it covers. Fixed point
// (u_scale units per 1.0) with integer atomics on a buffer: the sums are exact, so the order of
// the particles (and of the threads) cannot change the result.
//
// Cost per column is what matters on a CPU rasteriser: the Gaussian exp(-(a dx^2 + b dy^2)) is
// separable, so it is one exp per row and a running product along it (E_(i+1) = E_i R_i,
// R_(i+1) = R_i Q); log G = log(ac + (1 - ac) exp(-tau f)) without branches (its absolute error
// in float is ~1e-7, below the fixed point's step). The particles come sorted by footprint size,
// so the lanes of a SIMD batch loop alike.
layout(local_size_x = 64) in;

struct GridParticle {
    vec4 grid;    // gx, gy, gz (centre), gw0 (shadow-start depth before the shear)
    vec4 optics;  // radius (m), tau, albedo, 0
};
layout(std430, binding = 0) readonly buffer Particles { GridParticle particles[]; };
layout(std430, binding = 1) buffer Sums { int sums[]; };  // voxel (i, j, k) at (k ny + j) nx + i
uniform uint u_count;
uniform float u_scale;

void main()
{
    uint id = gl_GlobalInvocationID.x;
    if (id >= u_count)
        return;
    GridParticle p = particles[id];
    float r = p.optics.x, tau = p.optics.y;
    if (!(r > 0.0) || !(tau > 0.0))
        return;
    float ac = clamp(p.optics.z, 0.0, 1.0) * clamp(u_forward, 0.0, 1.0);
    float e0 = exp(-1.0 / (2.0 * kFootprintSigma * kFootprintSigma));
    // Columns whose centre lies within r of the axis.
    vec2 reach = vec2(r) / u_grid_voxel.xy;
    int i0 = max(0, int(ceil(p.grid.x - reach.x - 0.5))), i1 = min(u_grid_size.x - 1, int(floor(p.grid.x + reach.x - 0.5)));
    int j0 = max(0, int(ceil(p.grid.y - reach.y - 0.5))), j1 = min(u_grid_size.y - 1, int(floor(p.grid.y + reach.y - 0.5)));
    vec2 alpha = u_grid_voxel.xy * u_grid_voxel.xy / (2.0 * kFootprintSigma * kFootprintSigma * r * r);
    float x0 = float(i0) + 0.5 - p.grid.x;
    float row_e = exp(-alpha.x * x0 * x0), row_r = exp(-alpha.x * (2.0 * x0 + 1.0)), q = exp(-2.0 * alpha.x);
    float r2 = r * r;
    int layer = u_grid_size.x * u_grid_size.y;
    for (int j = j0; j <= j1; ++j) {
        float dy = float(j) + 0.5 - p.grid.y;
        float e = row_e * exp(-alpha.y * dy * dy), step = row_r;
        float dy2 = dy * dy * u_grid_voxel.y * u_grid_voxel.y;
        float s = p.grid.w - u_grid_shear_cells.y * (float(j) + 0.5);
        for (int i = i0; i <= i1; ++i, e *= step, step *= q) {
            float dx = (float(i) + 0.5 - p.grid.x) * u_grid_voxel.x;
            if (!(dx * dx + dy2 < r2))
                continue;
            float k = ceil(s - u_grid_shear_cells.x * (float(i) + 0.5) - 0.5);
            if (k >= float(u_grid_size.z))
                continue;
            float f = max(e - e0, 0.0) / (1.0 - e0);
            float log_g = clamp(log(ac + (1.0 - ac) * exp(-tau * f)), kMinLogGain, 0.0);
            int quantum = int(floor(log_g * u_scale + 0.5));
            if (quantum != 0)
                atomicAdd(sums[max(int(k), 0) * layer + j * u_grid_size.x + i], quantum);
        }
    }
}
