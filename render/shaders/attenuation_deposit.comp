#version 450 core
// Attenuation buffer, pass 1 (light_grid.hpp, attenuation_cpu.hpp): every particle adds log G of
// its footprint to the first voxel of its shadow cylinder in each column it covers. Fixed point
// (u_scale units per 1.0) with integer atomics on a buffer: the sums are exact, so the order of
// the particles (and of the threads) cannot change the result.
//
// Cost per column is what matters on a CPU rasteriser: the Gaussian exp(-(a dx^2 + b dy^2)) is
// separable, so it is one exp per row and a running product along it (E_(i+1) = E_i R_i,
// R_(i+1) = R_i Q); log G = log(1 - b (1 - exp(-t))), b = 1 - ac, t = tau f, is its Taylor
// polynomial in t for thin particles (tau <= 0.1: the first term left out is below 1e-6 of the
// value) and exp + log otherwise (absolute error ~1e-7 in float, below the fixed point's step).
// The particles come sorted by footprint size, so the lanes of a SIMD batch loop alike.
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Particles { GpuParticle particles[]; };
layout(std430, binding = 1) buffer Sums { int sums[]; };  // voxel (i, j, k) at (k ny + j) nx + i
uniform uint u_count;
uniform float u_scale;

void main()
{
    uint id = gl_GlobalInvocationID.x;
    if (id >= u_count)
        return;
    GpuParticle particle = particles[id];
    float r = particle.position_radius.w, tau = particle.optics.x;
    if (!(r > 0.0) || !(tau > 0.0))
        return;
    float ac = clamp(particle.optics.y, 0.0, 1.0) * clamp(u_forward, 0.0, 1.0);
    vec3 g = grid_of(particle.position_radius.xyz);
    vec4 p_grid = vec4(g, shadow_grid(g).z);  // gx, gy, gz, gw0
    float e0 = exp(-1.0 / (2.0 * kFootprintSigma * kFootprintSigma));
    // Columns whose centre lies within r of the axis.
    vec2 reach = vec2(r) / u_grid_voxel.xy;
    int i0 = max(0, int(ceil(p_grid.x - reach.x - 0.5))), i1 = min(u_grid_size.x - 1, int(floor(p_grid.x + reach.x - 0.5)));
    int j0 = max(0, int(ceil(p_grid.y - reach.y - 0.5))), j1 = min(u_grid_size.y - 1, int(floor(p_grid.y + reach.y - 0.5)));
    vec2 alpha = u_grid_voxel.xy * u_grid_voxel.xy / (2.0 * kFootprintSigma * kFootprintSigma * r * r);
    float x0 = float(i0) + 0.5 - p_grid.x;
    float row_e = exp(-alpha.x * x0 * x0), row_r = exp(-alpha.x * (2.0 * x0 + 1.0)), q = exp(-2.0 * alpha.x);
    float r2 = r * r;
    // log(1 - b (1 - e^-t)) = c1 t + c2 t^2 + c3 t^3 + c4 t^4 + O(t^5).
    float b = 1.0 - ac;
    bool thin = tau <= 0.1;
    vec4 taylor = vec4(-b, 0.5 * b * (1.0 - b), -b / 6.0 + 0.5 * b * b - b * b * b / 3.0,
                       b / 24.0 - 7.0 * b * b / 24.0 + 0.5 * b * b * b - 0.25 * b * b * b * b);
    int layer = u_grid_size.x * u_grid_size.y;
    for (int j = j0; j <= j1; ++j) {
        float dy = float(j) + 0.5 - p_grid.y;
        // The chord of the disc in this row (columns within r of the axis).
        float chord = sqrt(max(reach.x * reach.x * (1.0 - dy * dy / (reach.y * reach.y)), 0.0));
        int a = max(i0, int(ceil(p_grid.x - chord - 0.5))), z = min(i1, int(floor(p_grid.x + chord - 0.5)));
        float xa = float(a) + 0.5 - p_grid.x;
        float e = exp(-alpha.x * xa * xa - alpha.y * dy * dy), step = exp(-alpha.x * (2.0 * xa + 1.0));
        float dy2 = dy * dy * u_grid_voxel.y * u_grid_voxel.y;
        float s = p_grid.w - u_grid_shear_cells.y * (float(j) + 0.5);
        for (int i = a; i <= z; ++i, e *= step, step *= q) {
            float dx = (float(i) + 0.5 - p_grid.x) * u_grid_voxel.x;
            if (!(dx * dx + dy2 < r2))
                continue;
            float k = ceil(s - u_grid_shear_cells.x * (float(i) + 0.5) - 0.5);
            if (k >= float(u_grid_size.z))
                continue;
            float t = tau * max(e - e0, 0.0) / (1.0 - e0);
            float log_g = thin ? t * (taylor.x + t * (taylor.y + t * (taylor.z + t * taylor.w)))
                               : clamp(log(ac + b * exp(-t)), kMinLogGain, 0.0);
            int quantum = int(floor(log_g * u_scale + 0.5));
            if (quantum != 0)
                atomicAdd(sums[max(int(k), 0) * layer + j * u_grid_size.x + i], quantum);
        }
    }
}
