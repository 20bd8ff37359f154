// geometry::fitted_sun_scattering (fog_lighting.hpp), the fitted multiple scattering every fog
// renderer shares: a library listed before froxel_medium.glsl, layers.frag and particles.frag.
// Its own phase function, so it clashes with none of theirs when combined mode links them.
float fitted_hg(float cos_theta, float g)
{
    float d = 1.0 + g * g - 2.0 * g * clamp(cos_theta, -1.0, 1.0);
    return (1.0 - g * g) / (12.566370614359172 * d * sqrt(d));
}

// Single scattering plus the orders of
// scattering along the sun's path, with geometry::MultipleScatteringFit's constants.
float fitted_sun_scattering(float cos_theta, float g, float albedo, float tau, float sun_sine)
{
    const float amplitude = 3.09, sun_power = 0.454, persistence = 0.768, eccentricity = 0.491;
    const float diffuse_eccentricity = -0.439, low_sun_eccentricity = 0.471;
    const int orders = 4;  // geometry::fitted_orders
    g = clamp(g, -0.999, 0.999);
    float s = clamp(sun_sine, 0.0, 1.0);
    float b = persistence * clamp(albedo, 0.0, 1.0);
    float forward = low_sun_eccentricity * (1.0 - s);  // the lower the sun, the more forward
    float c = clamp(eccentricity + forward, 0.0, 1.0);
    float single = exp(-tau);
    float multiple = 0.0, weight = single * b * tau, taken = single, e = g * c;
    for (int n = 1; n + 1 < orders; ++n) {
        multiple += weight * fitted_hg(cos_theta, e);
        taken += weight;
        weight *= b * tau / float(n + 1);
        e *= c;
    }
    float rest = max(exp(-(1.0 - b) * tau) - taken, 0.0);  // every higher order
    multiple += rest * fitted_hg(cos_theta, clamp(diffuse_eccentricity + forward, -1.0, 1.0) * g);
    return single * fitted_hg(cos_theta, g) + amplitude * pow(max(s, 1e-6), sun_power) * multiple;
}

// (1 - e^-x) / x, 1 at 0.
float fog_exp_mean(float x) { return abs(x) < 1e-4 ? 1.0 - 0.5 * x : (1.0 - exp(-x)) / x; }

// The two-point Gauss rule of the weight e^(-c u) on [0, 1], c >= 0, over its mass: the mean of
// f under that weight is about w.x f(u.x) + w.y f(u.y), exact for cubics. A march's step or a
// layer's slab weighs its light so (what lies in front of each point lets it through), where the
// sun's share falls steeply across it (a dense fog's sunlit skin). From the weight's moments,
// m_k = (k m_(k-1) - e^-c) / c; near c = 0, where they cancel, Gauss-Legendre's nodes with the
// weight folded into w.
void exp_weight_gauss_rule(float c, out vec2 u, out vec2 w)
{
    u = vec2(0.5 - 0.5 / sqrt(3.0), 0.5 + 0.5 / sqrt(3.0));
    if (!(c > 0.5)) {
        w = 0.5 * exp(-c * u) / fog_exp_mean(c);
        return;
    }
    float e = exp(-c), m0 = (1.0 - e) / c;
    float m1 = (m0 - e) / c, m2 = (2.0 * m1 - e) / c, m3 = (3.0 * m2 - e) / c;
    m1 /= m0;
    m2 /= m0;
    m3 /= m0;
    float alpha = (m1 * m2 - m3) / max(m2 - m1 * m1, 1e-30), beta = -m2 - alpha * m1;
    float root = sqrt(max(0.25 * alpha * alpha - beta, 0.0));
    u = clamp(vec2(-0.5 * alpha - root, -0.5 * alpha + root), 0.0, 1.0);
    w.x = u.y > u.x ? clamp((u.y - m1) / (u.y - u.x), 0.0, 1.0) : 1.0;
    w.y = 1.0 - w.x;
}
