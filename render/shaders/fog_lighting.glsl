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
