#version 450 core
// A fog layer: the atlas alpha (border fade), the layer's alpha with the spacing correction
// 1 - (1 - a)^(r / r0) (thinner layers when more are added, so the stack keeps its optical
// thickness), world-space detail noise drifting with the wind, and a soft fade where the
// layer meets the ground (terrain height read per fragment). Output is premultiplied.
in vec3 v_world;
in vec2 v_uv;
in float v_alpha;
in float v_exponent;
flat in int v_layer;

uniform sampler2D u_atlas;
uniform sampler2D u_noise;       // tileable value noise (noise_texture.cpp)
uniform sampler2D u_heights;     // terrain heights (world metres), R32F
uniform vec4 u_height_rect;      // x0, y0, 1 / extent x, 1 / extent y
uniform vec2 u_height_texels;    // nx, ny
uniform float u_opacity;
uniform float u_ground_fade;
uniform float u_detail;
uniform float u_detail_scale;
uniform vec2 u_drift;            // wind * time (metres)
uniform vec3 u_eye;
uniform vec3 u_sun_direction;
uniform vec3 u_sun_radiance;
uniform vec3 u_ambient;
uniform vec3 u_sky_horizon;
uniform float u_haze_density;
out vec4 o_color;  // premultiplied linear radiance

// Detail: a tileable noise texture, shifted per layer so neighbouring layers differ.
float detail_noise(vec2 xy, float layer)
{
    // The tile holds 8 of the largest features: it repeats every 8 detail_scale metres.
    vec2 q = (xy - u_drift) / (8.0 * u_detail_scale) + layer * vec2(0.137, 0.071);
    return texture(u_noise, q).r;
}

void main()
{
    vec4 tex = texture(u_atlas, v_uv);
    float a = v_alpha * u_opacity * tex.a;
    if (u_detail > 0.0)
        a *= 1.0 - u_detail + u_detail * smoothstep(0.25, 0.75, detail_noise(v_world.xy, float(v_layer)));
    a = 1.0 - pow(max(1.0 - a, 0.0), v_exponent);
    vec2 h_uv = (v_world.xy - u_height_rect.xy) * u_height_rect.zw;
    h_uv = (h_uv * (u_height_texels - 1.0) + 0.5) / u_height_texels;  // texel centres at the samples
    float clearance = v_world.z - texture(u_heights, h_uv).r;
    a *= u_ground_fade > 0.0 ? smoothstep(0.0, u_ground_fade, clearance) : step(0.0, clearance);
    if (a <= 1e-6)  // nothing to add; a larger threshold would bias stacks of many thin layers
        discard;
    // Gray, lit by the sun (forward scattering brightens it towards the sun) and the sky.
    vec3 view = normalize(v_world - u_eye);
    float cos_sun = dot(view, u_sun_direction);
    float phase = 0.55 + 0.45 * (1.0 + cos_sun * cos_sun) * 0.5 + 0.5 * pow(max(cos_sun, 0.0), 8.0);
    float sun_up = clamp(u_sun_direction.z * 2.0 + 0.2, 0.0, 1.0);
    vec3 radiance = tex.rgb * (u_sun_radiance * sun_up * phase * 0.6 + u_ambient * 1.6);
    float haze = 1.0 - exp(-length(v_world - u_eye) * u_haze_density);
    radiance = mix(radiance, u_sky_horizon, haze);
    o_color = vec4(radiance * a, a);
}
