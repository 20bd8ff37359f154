// Library (inserted after #version): one particle's footprint and the attenuation buffer's
// lookup, the GPU copy of geometry/include/kiri/geometry/particles/particle_footprint.hpp and of
// sample_log_gamma / self_log_gamma in attenuation_cpu.hpp (a GL test checks they agree).

const float kFootprintSigma = 0.4;
const float kMinLogGain = -16.0;
const float kMinLogGamma = -80.0;
const float kOwnShare = 0.5;  // geometry::billboard_own_share (attenuation_cpu.hpp)

// f(x) = (exp(-x^2 / 2s^2) - e0) / (1 - e0) for x < 1, else 0.
float footprint_profile(float x)
{
    if (!(x < 1.0))
        return 0.0;
    float e0 = exp(-1.0 / (2.0 * kFootprintSigma * kFootprintSigma));
    return (exp(-x * x / (2.0 * kFootprintSigma * kFootprintSigma)) - e0) / (1.0 - e0);
}

// erf by Abramowitz and Stegun 7.1.26 (absolute error below 1.5e-7).
float erf_approx(float x)
{
    float t = 1.0 / (1.0 + 0.3275911 * abs(x));
    float y = 1.0 - t * (0.254829592 + t * (-0.284496736 + t * (1.421413741 + t * (-1.453152027 + t * 1.061405429)))) * exp(-x * x);
    return x < 0.0 ? -y : y;
}

// footprint_ray_share (particle_footprint.hpp): of the column a ray passing x = rho / r from a
// particle's centre crosses, the share between u0 and u1 (metres along the ray from its point
// nearest the centre). The particle in three dimensions is the footprint's Gaussian,
// exp(-q^2 / 2 (s r)^2) - e0 at distance q < r from its centre.
// The same with g = exp(-x^2 / 2s^2) given: the chord's parts share it.
float chord_integral_at(float g, float u)
{
    float e0 = exp(-1.0 / (2.0 * kFootprintSigma * kFootprintSigma));
    return 1.2533141373155 * kFootprintSigma * g * erf_approx(u * 0.70710678118655 / kFootprintSigma) - e0 * u;
}
float chord_integral(float x, float u)  // from 0 to u along the chord, radius 1
{
    return chord_integral_at(exp(-x * x / (2.0 * kFootprintSigma * kFootprintSigma)), u);
}
// The part of the chord at x between u0 and u1 in units of the radius, within the half chord
// (chord_part in particle_footprint.cpp): false when the ray misses the ball or the part is empty.
bool chord_part(inout float x, float radius, float u0, float u1, out float a, out float b, out float half_chord)
{
    a = 0.0;
    b = 0.0;
    half_chord = 0.0;
    if (!(x < 1.0) || !(radius > 0.0))
        return false;
    x = max(x, 0.0);
    half_chord = sqrt(1.0 - x * x);
    a = clamp(u0 / radius, -half_chord, half_chord);
    b = clamp(u1 / radius, -half_chord, half_chord);
    return b > a;
}
float footprint_ray_share(float x, float radius, float u0, float u1)
{
    float a, b, half_chord;
    if (!chord_part(x, radius, u0, u1, a, b, half_chord))
        return 0.0;
    float whole = 2.0 * chord_integral(x, half_chord);
    // At the rim float loses the integral to cancellation; the density is nearly even along so
    // short a chord: share by length (the CPU's threshold is lower).
    if (!(whole > 1e-4))
        return (b - a) / (2.0 * half_chord);
    return clamp((chord_integral(x, b) - chord_integral(x, a)) / whole, 0.0, 1.0);
}

// log G, G = T + a c (1 - T), T = exp(-tau f(rho / r)), clamped to [kMinLogGain, 0].
float footprint_log_gain(float rho, float radius, float tau, float albedo, float forward)
{
    if (!(radius > 0.0) || !(tau > 0.0))
        return 0.0;
    float f = footprint_profile(rho / radius);
    if (f <= 0.0)
        return 0.0;
    float t = tau * f;
    float ac = clamp(albedo, 0.0, 1.0) * clamp(forward, 0.0, 1.0);
    float g;
    if (ac <= 0.0)
        g = -t;
    else if (t > 80.0)
        g = log(ac);
    else  // -t + log1p(ac (e^t - 1)), written for float: small t keeps its digits through ac t
        g = t < 1e-3 ? -t + log(1.0 + ac * t * (1.0 + 0.5 * t)) : -t + log(1.0 + ac * (exp(t) - 1.0));
    return clamp(g, kMinLogGain, 0.0);
}

// A particle as the GPU holds it (render/src/particle_gpu.hpp): position relative to the cloud's
// centre and radius; optical depth and albedo.
struct GpuParticle {
    vec4 position_radius;
    vec4 optics;  // tau, albedo, the billboard's and the light's gain on tau (seen_gain), 0
    // The fog's floor where it floats above the ground and its top: each plane's height at the
    // particle's centre relative to the cloud's centre (or -1e30 and 1e30: none) and its dz/dx,
    // dz/dy.
    vec4 floor_plane;
    vec4 top_plane;
};

// The attenuation buffer's grid (light_grid.hpp) in voxel units.
uniform mat4 u_to_grid;           // position relative to the cloud's centre -> grid coordinates
uniform ivec3 u_grid_size;
uniform vec3 u_grid_voxel;        // du, dv, dw (metres)
uniform vec2 u_grid_shear_cells;  // a du / dw, b dv / dw
uniform float u_forward;          // p(l,l) / 4pi
uniform vec3 u_grid_u_axis;       // the grid's axes in the world: across the light (u, v) and
uniform vec3 u_grid_v_axis;       // towards the sun (LightGrid::u_axis, v_axis, light)
uniform vec3 u_grid_light;

// A particle as the light's columns see it: its ball cut at the planes of the fog's floor and
// top, the mass cut off there and in the ground given back to the rest (column_log_gain).
struct Ball {
    vec3 centre;       // relative to the cloud's centre
    vec3 optics;       // radius, tau times its gain (GpuParticle.optics.z), albedo
    vec3 floor_plane;  // as GpuParticle's: below -1e29 none
    vec3 top_plane;    // over 1e29 none
};
Ball ball_of(GpuParticle p)
{
    return Ball(p.position_radius.xyz, vec3(p.position_radius.w, p.optics.x * p.optics.z, p.optics.y),
                p.floor_plane.xyz, p.top_plane.xyz);
}
// Whether a plane cuts the ball (side 1: a floor, the fog over it; -1: a top).
bool plane_cuts(vec3 plane, float side, Ball b)
{
    return side * (b.centre.z - plane.x) < b.optics.x * sqrt(1.0 + dot(plane.yz, plane.yz));
}
bool planes_cut(Ball b)
{
    return (b.floor_plane.x > -1e29 && plane_cuts(b.floor_plane, 1.0, b)) ||
        (b.top_plane.x < 1e29 && plane_cuts(b.top_plane, -1.0, b));
}
// Clips the span [span.x, span.y] of the line point + t dir (t in metres) to the side of a plane
// the fog lies on: over it (side 1, a floor) or under it (side -1, a top). The plane: its height
// at the particle's centre and its dz/dx, dz/dy; `height` the point's z, `offset` the point's
// (x, y) less the centre's, all relative to the cloud's centre. A light column through a ball
// (column_plane_share) and a view ray through a billboard (particles.frag) are cut alike.
void clip_line_to_plane(vec3 plane, float side, float height, vec2 offset, vec3 dir, inout vec2 span)
{
    float above = side * (height - plane.x - dot(plane.yz, offset));
    float rise = side * (dir.z - dot(plane.yz, dir.xy));
    if (rise > 0.0)
        span.x = max(span.x, -above / rise);
    else if (rise < 0.0)
        span.y = min(span.y, -above / rise);
    else if (above < 0.0)
        span.y = -1e30;
}
// The share of the ball's column at `offset` (metres across the light from its axis, along the
// grid's u and v) between its planes.
float column_plane_share(vec2 offset, Ball b)
{
    bool floor_cut = b.floor_plane.x > -1e29, top_cut = b.top_plane.x < 1e29;
    if (!floor_cut && !top_cut)
        return 1.0;
    vec3 o = offset.x * u_grid_u_axis + offset.y * u_grid_v_axis;
    vec2 span = vec2(-1e30, 1e30);
    if (floor_cut)
        clip_line_to_plane(b.floor_plane, 1.0, b.centre.z + o.z, o.xy, u_grid_light, span);
    if (top_cut)
        clip_line_to_plane(b.top_plane, -1.0, b.centre.z + o.z, o.xy, u_grid_light, span);
    return footprint_ray_share(length(offset) / b.optics.x, b.optics.x, span.x, span.y);
}
// log G of the ball's footprint in the light column at `offset` (column_log_gain).
float column_log_gain(vec2 offset, Ball b)
{
    float rho = length(offset);
    if (!(rho < b.optics.x))
        return 0.0;
    float share = column_plane_share(offset, b);
    return share > 0.0 ? footprint_log_gain(rho, b.optics.x, b.optics.y * share, b.optics.z, u_forward) : 0.0;
}

vec3 grid_of(vec3 relative) { return (u_to_grid * vec4(relative, 1.0)).xyz; }
// A particle's (gx, gy, gw0): gw0 is its depth before the shear, where its shadow starts in
// column (i, j) at gw0 - a' (i + 0.5) - b' (j + 0.5) (LightGrid::shadow_start).
vec3 shadow_grid(vec3 g) { return vec3(g.xy, g.z + u_grid_shear_cells.x * g.x + u_grid_shear_cells.y * g.y); }

// GL_LINEAR + GL_CLAMP_TO_EDGE along one axis: texels (x, y) and the weight of the second (z).
vec3 linear_taps(float g, int n)
{
    float x = g - 0.5;
    float f = floor(x);
    int i = int(clamp(f, -1.0, float(n)));
    return vec3(float(clamp(i, 0, n - 1)), float(clamp(i + 1, 0, n - 1)), x - f);
}

// The log gain of a particle's footprint in light column c (its deposit there): the particle at
// grid coordinates (gx, gy) with shadow-start depth gw0 (before the shear).
float column_self_log_gain(ivec2 c, vec3 self_grid, Ball self_ball)
{
    return column_log_gain((vec2(c) + 0.5 - self_grid.xy) * u_grid_voxel.xy, self_ball);
}

// The share of column c's deposit that a trilinear read with depth taps tz takes: the read's
// depth weights of the voxels at or beyond the particle's shadow start in that column.
float self_depth_weight(ivec2 c, vec3 self_grid, vec3 tz)
{
    float s = self_grid.z - u_grid_shear_cells.x * (float(c.x) + 0.5) - u_grid_shear_cells.y * (float(c.y) + 0.5);
    float start = max(ceil(s - 0.5), 0.0);
    return (tz.x >= start ? 1.0 - tz.z : 0.0) + (tz.y >= start ? tz.z : 0.0);
}

// What the trilinear read at grid point g holds of a particle's own cylinder (its deposit in the
// read's four columns, weighted as the filter weighs them).
float self_log_gamma(vec3 g, vec3 self_grid, Ball self_ball)
{
    vec3 tx = linear_taps(g.x, u_grid_size.x), ty = linear_taps(g.y, u_grid_size.y), tz = linear_taps(g.z, u_grid_size.z);
    float sum = 0.0;
    for (int dj = 0; dj < 2; ++dj)
        for (int di = 0; di < 2; ++di) {
            ivec2 c = ivec2(di == 0 ? tx.x : tx.y, dj == 0 ? ty.x : ty.y);
            float gain = column_self_log_gain(c, self_grid, self_ball);
            if (gain != 0.0)
                sum += (di == 0 ? 1.0 - tx.z : tx.z) * (dj == 0 ? 1.0 - ty.z : ty.z) * self_depth_weight(c, self_grid, tz) * gain;
        }
    return sum;
}

// own_column_log_gain (attenuation_cpu.hpp): the particle's footprint in the read's four columns,
// weighted as the read weighs them, over the whole column (as if its shadow started before g).
float own_column_log_gain(vec3 g, vec3 self_grid, Ball self_ball)
{
    vec3 tx = linear_taps(g.x, u_grid_size.x), ty = linear_taps(g.y, u_grid_size.y);
    float sum = 0.0;
    for (int dj = 0; dj < 2; ++dj)
        for (int di = 0; di < 2; ++di) {
            ivec2 c = ivec2(di == 0 ? tx.x : tx.y, dj == 0 ? ty.x : ty.y);
            sum += (di == 0 ? 1.0 - tx.z : tx.z) * (dj == 0 ? 1.0 - ty.z : ty.z) * column_self_log_gain(c, self_grid, self_ball);
        }
    return sum;
}

// log Gamma at grid point g for the particle described by self_grid / self_ball (it does not
// shade itself, Harris's particle at its centre): trilinear log Gamma - its own part.
float particle_log_gamma(sampler3D log_gamma, vec3 g, vec3 self_grid, Ball self_ball)
{
    float raw = texture(log_gamma, g / vec3(u_grid_size)).r;
    return clamp(raw - self_log_gamma(g, self_grid, self_ball), kMinLogGamma, 0.0);
}
float particle_gamma(sampler3D log_gamma, vec3 g, vec3 self_grid, Ball self_ball)
{
    return exp(particle_log_gamma(log_gamma, g, self_grid, self_ball));
}

// Henyey-Greenstein (1/sr), g clamped to [-0.999, 0.999].
float henyey_greenstein(float cos_theta, float g)
{
    g = clamp(g, -0.999, 0.999);
    float denom = 1.0 + g * g - 2.0 * g * clamp(cos_theta, -1.0, 1.0);
    return (1.0 - g * g) / (4.0 * 3.14159265358979 * denom * sqrt(denom));
}
