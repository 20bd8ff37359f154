// Library of the layers' fog (layers.frag, layers_end.frag): the Medium's detail noise as a layer
// takes it, and the shared lighting model (geometry::fog_source) of a slab of it.
uniform sampler2D u_noise;       // tileable value noise (geometry::fog_noise_tile)
uniform float u_detail;
uniform float u_detail_scale;
uniform float u_detail_layers;  // the noise's shift with height, in layers (the Medium's detail_layers)
uniform vec2 u_drift;            // wind * time (metres)
uniform vec3 u_sun_direction;
uniform vec3 u_sun_radiance;
uniform vec3 u_ambient;
uniform float u_albedo;
uniform float u_anisotropy;      // g, clamped inside (-1, 1) on the CPU
uniform float u_count;           // l0, the reference stack's layers
uniform int u_octaves;           // multiple-scattering octaves (geometry::fog_source)
uniform vec3 u_eye;
uniform int u_eye_inside;        // 1: the eye lies inside the stack (geometry::layers_under_eye)
uniform float u_eye_base;        // the base under the eye and the layers' spacing there
uniform float u_eye_spacing;     // (geometry::layer_stack_under): layer i at u_eye_base + i u_eye_spacing
uniform float u_first_reach;     // metres within which a ray may still be in the space it started in
uniform sampler2D u_frame_depth; // the frame's resolved depth (the stretch pass, and the layers with it)
uniform mat4 u_inverse_view_projection;

// The world point at uv ([0, 1]^2 over the target) and window depth `depth`.
vec3 unproject(vec2 uv, float depth)
{
    vec4 h = u_inverse_view_projection * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    return h.xyz / h.w;
}

#if defined(LAYERS_AT_SAMPLES)
uniform sampler2DMS u_frame_samples;  // the frame's samples' depth (4 of them)
uniform vec2 u_sample_offsets[8];     // each sample's offset from the pixel's centre (pixels, GL's y up)

// Where sample s of this fragment's pixel lies on the target at the frame's resolution (uv).
vec2 sample_uv(int s)
{
    return (floor(gl_FragCoord.xy) + 0.5 + u_sample_offsets[s]) / vec2(textureSize(u_frame_samples));
}

// The terrain point sample s of this fragment's pixel sees; false: the sky.
bool sample_ground(int s, out vec3 ground)
{
    float depth = texelFetch(u_frame_samples, ivec2(gl_FragCoord.xy), s).r;
    if (!(depth < 1.0))
        return false;
    ground = unproject(sample_uv(s), depth);
    return true;
}

// The distance from the eye to it (1e30: the sky).
float sample_ground_distance(int s)
{
    vec3 ground;
    return sample_ground(s, ground) ? distance(ground, u_eye) : 1e30;
}
#endif

const float pi = 3.14159265358979;

// The terrain point the frame's depth holds at uv ([0, 1]^2 over the target); false: the sky. The
// stretch pass and the layers take the same sample for a texel, so where one's fog ends the
// other's begins.
bool frame_ground(vec2 uv, out vec3 ground)
{
    float depth = texture(u_frame_depth, uv).r;
    if (!(depth < 1.0))
        return false;
    ground = unproject(uv, depth);
    return true;
}

// Detail: a tileable noise texture, shifted with height so neighbouring layers differ. `layer` is
// the height in the fog h times the Medium's detail_layers, as Medium::detail_factor takes it:
// a layer shows the Medium's noise of its height whatever the stack's count, and the narrowing's
// added layers near the eye theirs.
float detail_noise(vec2 xy, float layer)
{
    // The tile holds 8 of the largest features: it repeats every 8 detail_scale metres.
    vec2 q = (xy - u_drift) / (8.0 * u_detail_scale) + layer * vec2(0.137, 0.071);
    return texture(u_noise, q).r;
}

float henyey_greenstein(float cos_theta, float g)
{
    float d = 1.0 + g * g - 2.0 * g * cos_theta;
    return (1.0 - g * g) / (4.0 * pi * d * sqrt(d));
}

// S of geometry::fog_source (fog_lighting.hpp): the sun's phase and transmittance through tau_sun;
// u_octaves 0: the fitted model, else that many octaves.
float sun_scattering(float cos_theta, float tau_sun)
{
    float sun = 0.0, a = 1.0, b = 1.0, c = 1.0;
    if (u_octaves == 0)
        sun = fitted_sun_scattering(cos_theta, u_anisotropy, u_albedo, tau_sun, u_sun_direction.z);
    for (int i = 0; i < u_octaves; ++i, a *= 0.5, b *= 0.5, c *= 0.5)
        sun += a * henyey_greenstein(cos_theta, c * u_anisotropy) * exp(-b * tau_sun);
    return sun;
}

// geometry::fog_source: the source per unit extinction towards the eye, with S given.
vec3 fog_source_of(float sun, float visibility) { return u_albedo * (pi * visibility * sun * u_sun_radiance + u_ambient); }

vec3 fog_source(float cos_theta, float tau_sun, float visibility)
{
    return fog_source_of(sun_scattering(cos_theta, tau_sun), visibility);
}

// S over a slab the ray crosses with optical depth `depth`, tau_sun linear from tau0 where it
// enters to tau1 where it leaves (exact under a flat top), weighted by what the slab lets through
// in front of each point. A dense fog's top slab is lit in its first metres, which its middle
// does not see (the layers 18 % too dark over a lake of 10 m visibility). S e^(gain u) is smooth
// (no model falls faster than e^-tau_sun), integrated against e^-(depth + gain) u by that
// weight's two-point Gauss rule (exp_weight_gauss_rule, fog_lighting.glsl), as a march's step
// (froxel_light.glsl's sun_share_over_step).
float sun_scattering_over_slab(float cos_theta, float tau0, float tau1, float depth)
{
    float gain = max(tau1 - tau0, 0.0);
    vec2 u, w;
    exp_weight_gauss_rule(depth + gain, u, w);
    float mean = 0.0;
    for (int i = 0; i < 2; ++i)
        mean += w[i] * sun_scattering(cos_theta, mix(tau0, tau1, u[i])) * exp(gain * u[i]);
    return mean * fog_exp_mean(depth + gain) / fog_exp_mean(depth);
}

// Of the light a slab of optical depth tau scatters along a path of length `path` into it, the
// mean distance from where the ray enters: the weights exp(-sigma t) over [0, path].
float emission_centroid(float path, float tau)
{
    if (!(tau > 1e-3))
        return path * (0.5 - tau / 12.0);
    return path * (1.0 / tau - 1.0 / (exp(min(tau, 80.0)) - 1.0));
}

// The space between layers j and j + 1 that a ray from the eye starts in (-1: under the base),
// taken a hundredth of a spacing along the ray: an eye on a layer starts on the side the ray
// leaves to.
float eye_region(vec3 view)
{
    return floor((u_eye.z + view.z * 0.01 * u_eye_spacing - u_eye_base) / u_eye_spacing);
}

// The terrain's visibility of the sun over the light a path scatters towards the eye, from
// `start` along `view` for `path` metres of optical depth `tau`: the mean at `n` points, each
// holding an equal share of the emission. A slab seen at a grazing angle, or the fog from the eye
// to its first layer, runs for hundreds of metres, often into the shade of a wall part of the way.
float path_visibility(vec3 start, vec3 view, float path, float tau, int n)
{
    float kept = 1.0 - exp(-tau), v = 0.0;
    for (int i = 0; i < n; ++i) {
        float u = (float(i) + 0.5) / float(n);
        float t = tau > 1e-4 ? -log(1.0 - u * kept) / tau * path : u * path;
        v += terrain_visibility(start + view * t, u_ts_bias);
    }
    return v / float(n);
}

// Points path_visibility takes along a path of `path` metres in fog whose layers lie `spacing`
// apart: one for a slab crossed steeply, up to 8 along a grazing one.
int visibility_points(float path, float spacing) { return clamp(int(path / (4.0 * spacing)), 1, 8); }
