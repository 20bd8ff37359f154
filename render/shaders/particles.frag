#version 450 core
// A particle billboard: opacity 1 - T from its Gaussian footprint along this fragment's ray, the
// part of the particle's column between the eye and the terrain (footprint_ray_share), lit by
// the fog's shared model (geometry::fog_source, fog_lighting.hpp) with the sun seen through the
// attenuation buffer: Gamma at this fragment (billboard_log_gamma, particle_light.glsl: the
// particle's own footprint counted as the Medium around it would be) stands for exp(-tau_sun),
// so octave i sees Gamma^(b^i); hazed with distance like the terrain; in the terrain's shadow
// from the sun (the renderer's shadow map, as the froxels and the CPU reference see it). Balls
// standing for the Medium (KIRI_DENSITY_RATIO) take its density over their sum along the ray and
// its own light (the sun volume, the shadow at the lit point), lit where their place in the blend
// puts them along the ray (rank_lit_offset). Blended back to front,
// premultiplied linear radiance: E_k = S_k + T_k E_(k-1) ([Shimada08] (5)), S_k = (1 - T) J.
in vec3 v_ray;
flat in vec3 v_centre;
flat in vec4 v_grid_visible;
flat in ivec4 v_window;
flat in uint v_table;
flat in float v_own_share;  // the share of its own column that shades it (particles.vert)
flat in vec3 v_optics;  // radius, tau times its gain (seen_gain), albedo
flat in float v_seen_tau;  // tau with the mass in the ground or cut off at a plane added (particles.vert)
flat in vec3 v_floor_plane;  // the fog's floor under it (particles.vert); below -1e29: none
flat in vec3 v_top_plane;    // the fog's top over it; over 1e29: none
flat in float v_footprint_radius;  // the radius drawn (particles.vert's u_radius_scale, widened)
flat in float v_depth_radius;      // the ball's extent along the rays
flat in vec2 v_centre_ndc;         // the centre on the screen (normalised device coordinates)
in vec4 v_fog;
flat in float v_baked;
flat in vec3 v_baked_slope;
uniform sampler3D u_log_gamma;
uniform sampler2D u_depth;       // the terrain's depth, full resolution
uniform vec2 u_depth_scale;      // its pixels per pixel of this target (the near target's are coarser)
uniform int u_lit;               // 0: no buffer (every particle fully lit)
uniform float u_near;
uniform float u_far;
uniform float u_soft_edge;       // metres
uniform vec3 u_eye;
uniform vec3 u_camera_forward;
uniform vec3 u_centre;  // the cloud's centre
uniform vec4 u_fog_xy;  // the (x, y) rectangle that holds the fog (min, max), relative to u_centre
uniform vec3 u_sky_horizon;
uniform float u_haze_density;
uniform float u_near_field;      // metres from the eye the near field covers (0: none)
#ifdef KIRI_DENSITY_RATIO
// The balls' summed density (density_ratio.hpp, DensityRatioTexture) over (x, y) and the shell's
// height from the column's floor to its top. The Medium's own extinction at a point
// (froxel_medium.glsl) over it is R, the weight of every ball's density there.
uniform sampler3D u_ratio;
uniform vec4 u_ratio_xy;  // the grid's (x0, y0) relative to u_centre; 1 / its width, 1 / its depth
uniform float u_ratio_max;
uniform float u_ratio_footprint;  // the ball's mass over its footprint's (geometry::ball_mass)
uniform vec3 u_sv_direction;      // the sun as the sun volume was built for (sun_march_direction)
// R at the middle of each third of a chord: the Medium's density changes along a ray within a
// ball (a thread's walls, the detail noise's layers); one point at the chord's middle drew a
// blanket seen from above 2.5 % too dark (a ball widened beyond a pixel took it at its centre).
const int kRatioPoints = 3;
#endif
out vec4 o_color;
#ifdef PARTICLES_AT_SAMPLES
// Samples 1..3's blends (o_color: sample 0's), over the frame's samples' depth (depth_samples.glsl:
// u_offsets).
layout(location = 1) out vec4 o_sample1;
layout(location = 2) out vec4 o_sample2;
layout(location = 3) out vec4 o_sample3;
uniform sampler2DMS u_samples_depth;
uniform vec3 u_camera_right;
uniform vec3 u_camera_up;
uniform vec2 u_tan_half;
#endif

#ifdef KIRI_DENSITY_RATIO
// R at a point relative to u_centre (geometry::density_ratio_at): the sum read at the height in
// the Medium's own column, which its density has looked up.
float density_ratio(vec3 p, out float sigma)
{
    vec3 world = p + u_centre;
    sigma = 0.0;
    if (u_md_on == 0 || !shell_covers(world.xy))
        return 0.0;
    vec4 column = shell_column(world.xy);
    float h;
    sigma = u_md_extinction * medium_density_in(world, column, h);
    if (!(sigma > 0.0))
        return 0.0;
    float level = column.z > column.x ? (world.z - column.x) / (column.z - column.x) : 0.0;
    float balls = texture(u_ratio, vec3((p.xy - u_ratio_xy.xy) * u_ratio_xy.zw, level)).r;
    return balls > 0.0 ? min(sigma / balls, u_ratio_max) : u_ratio_max;
}
#endif

// The part of a ray from the eye (`ray`, unit) in the ball's fog: [t0, t1] along it, in front of
// the ground `scene` metres along it, over the rectangle that holds the fog, between the fog's
// floor and top planes and beyond the near field.
vec2 visible_span(vec3 ray, float scene)
{
    // The part of the ray that lies in the fog: in front of the terrain and over the rectangle
    // that holds the fog (the Medium's grid: a particle at its edge would blur the fog's wall).
    float t0 = 0.0, t1 = scene;
    line_over_rect(u_eye - u_centre, ray, u_fog_xy.xy, u_fog_xy.zw, t0, t1);  // height_fog.glsl
    // And above the fog's floor where the fog floats over the ground (a blanket's bottom): seen
    // from under the blanket, a particle's ball below it would veil the clear air.
    // The floor's plane slopes with the blanket's bottom (a level plane under its lowest point
    // left slivers of the balls, which level rays under the bottom crossed by the hundred).
    // The ray from the eye (v_centre: the particle's centre from the eye), clipped as
    // particle_footprint.glsl's clip_line_to_plane clips a line.
    vec2 span = vec2(t0, t1);
    if (v_floor_plane.x > -1e29)
        clip_line_to_plane(v_floor_plane, 1.0, u_eye.z - u_centre.z, -v_centre.xy, ray, span);
    // And under the fog's top: seen level, a ball standing out of a lake's top veiled the far
    // shore (the part cut off is given back to the rest, as the ground's: seen_gain).
    if (v_top_plane.x < 1e29)
        clip_line_to_plane(v_top_plane, -1.0, u_eye.z - u_centre.z, -v_centre.xy, ray, span);
    // And beyond the near field (particles_near.frag marches the Medium itself within it).
    return vec2(max(span.x, u_near_field), span.y);
}

#ifdef KIRI_DENSITY_RATIO
// The ball's density times R along the part [a, b] of its chord at x (relative to `along`, the
// distance of the centre's foot on `ray`), in thirds, each weighted by R at its middle
// (geometry::ball_chord_share, from the chord integral at the thirds' ends; one g for them all).
float weighted_chord(vec3 ray, float along, float x, float a, float b, out float ball[kRatioPoints],
                     out float medium[kRatioPoints])
{
    float g = exp(-x * x / (2.0 * kFootprintSigma * kFootprintSigma));
    float whole_centre = 2.0 * chord_integral(0.0, 1.0);
    float before = chord_integral_at(g, a / v_depth_radius), weighted = 0.0;
    for (int k = 0; k < kRatioPoints; ++k) {
        float u0 = mix(a, b, float(k) / float(kRatioPoints)), u1 = mix(a, b, float(k + 1) / float(kRatioPoints));
        float after = chord_integral_at(g, u1 / v_depth_radius);
        float sigma;
        ball[k] = max(after - before, 0.0) / whole_centre *
                  density_ratio(u_eye - u_centre + ray * (along + 0.5 * (u0 + u1)), sigma);
        medium[k] = sigma * (u1 - u0);
        weighted += ball[k];
        before = after;
    }
    return weighted;
}

// Where along its visible chord [a, b] (relative to the centre's foot) a ball is lit, given its
// own optical depth `tau` there and, in thirds of the chord, its share of it (`ball`, summing to 1)
// and the Medium's optical depth (`medium`). The balls are blended in the order of their centres,
// so a ball's light is dimmed by the optical depth of the balls centred in front of it, which
// together carry the Medium's in front of its centre less its own part there; it stands for the
// stretch of the ray just beyond that depth, and scatters from it as a slab of its own tau, on
// average 1 - tau e^-tau / (1 - e^-tau) deep (tau / 2 in thin fog, one optical depth in dense).
// In thin fog that is the centre's foot; in dense fog, the skin the ray sees, where the nearest
// point to the centre lay metres under it, out of the sunlight (docs/particles.md, "Each ball lit
// where the blend puts it").
float rank_lit_offset(float a, float b, float tau, float ball[kRatioPoints], float medium[kRatioPoints])
{
    float third = (b - a) / float(kRatioPoints);
    float front = clamp(-a / max(third, 1e-6), 0.0, float(kRatioPoints));  // thirds before the centre's foot
    float medium_front = 0.0, own_front = 0.0, medium_all = 0.0;
    for (int k = 0; k < kRatioPoints; ++k) {
        float f = clamp(front - float(k), 0.0, 1.0);
        medium_front += f * medium[k];
        own_front += f * tau * ball[k];
        medium_all += medium[k];
    }
    if (!(medium_all > 1e-6))
        return clamp(0.0, a, b);
    float mean_depth = tau < 1e-3 ? 0.5 * tau : 1.0 - tau * exp(-tau) / max(1.0 - exp(-tau), 1e-6);
    float target = clamp(medium_front - own_front + mean_depth, 0.0, medium_all);
    float s = a;
    for (int k = 0; k < kRatioPoints; ++k) {
        float take = min(target, medium[k]);
        s += medium[k] > 0.0 ? third * take / medium[k] : (target > 0.0 ? third : 0.0);
        target -= take;
        if (!(target > 0.0))
            break;
    }
    return clamp(s, a, b);
}
#endif

// What this billboard's ball puts on a ray from the eye (`ray`, unit) that meets the ground at
// view depth `ground` (along the view axis; a widened billboard's along the ray through its
// centre, below, and `own_ground` the ray's own): its optical depth, where it is lit (`lit` along `lit_ray`: where the visible
// part passes nearest the centre; for balls standing for the Medium, where the blend puts it) and
// the distance to the ground along that ray.
struct Seen {
    float tau, lit, scene;
    vec3 lit_ray;
};

Seen seen_along(vec3 ray, bool widened, float ground, float own_ground)
{
    Seen seen = Seen(0.0, 0.0, 0.0, ray);
    float along = dot(v_centre, ray);
    float x = sqrt(max(dot(v_centre, v_centre) - along * along, 0.0)) / v_footprint_radius;
    if (x >= 1.0)
        return seen;
    // A billboard widened beyond its ball (particles.vert) spreads the ball's mass over pixels
    // whose rays miss the ball: what the terrain hides of it is taken at the depth of the pixel
    // its centre falls in, along the ray through it, not along rays that meet the ground in front
    // of it (a ball on the ground seen obliquely lost a quarter of its mass so).
    vec3 cut_ray = widened ? normalize(v_centre) : ray;
    seen.scene = ground / max(dot(cut_ray, u_camera_forward), 1e-6);
    vec2 span = visible_span(cut_ray, seen.scene);
    float t0 = span.x, t1 = span.y;
    float cut_along = widened ? length(v_centre) : along;
    // Spread over the pixels around it, but not over those whose own ray meets no fog (between
    // the fog's planes, in front of their own ground): seen level, a lake's far edge widened into
    // a veil over the shore behind it. Where the fog is thinner than a pixel is tall, a pixel's
    // ray crosses it at another depth than the ball's, so the ball's chord is not cut there.
    if (widened) {
        vec2 own = visible_span(ray, own_ground / max(dot(ray, u_camera_forward), 1e-6));
        if (!(own.y > own.x))
            return seen;
    }
    // The visible part relative to the chord's middle.
    float lo = t0 - cut_along, hi = t1 - cut_along;
    // Lit where the ray's visible part passes nearest the centre; a widened billboard's rays pass
    // up to a pixel from its ball (tens of metres from afar, out of a thin valley's fog and into
    // its walls' shadow), so it is lit on the ray through its centre, where its mass is.
    seen.lit_ray = cut_ray;
    seen.lit = cut_along + clamp(0.0, lo, max(lo, hi));
#ifdef KIRI_DENSITY_RATIO
    // The ball's density times R along the visible chord; for a billboard widened beyond its ball
    // (which spreads its footprint's mass), R's mean along the chord through its centre.
    float chord_x = widened ? 0.0 : x;
    float half_chord = v_depth_radius * sqrt(max(1.0 - chord_x * chord_x, 0.0));
    float a = clamp(lo, -half_chord, half_chord), b = clamp(hi, -half_chord, half_chord);
    if (!(b > a))
        return seen;
    float ball[kRatioPoints], medium[kRatioPoints];
    float weighted = weighted_chord(cut_ray, cut_along, chord_x, a, b, ball, medium);
    if (widened) {
        float mass = (chord_integral(0.0, b / v_depth_radius) - chord_integral(0.0, a / v_depth_radius)) /
                     (2.0 * chord_integral(0.0, 1.0));
        seen.tau = v_seen_tau * footprint_profile(x) *
                   footprint_ray_share(x, v_depth_radius, lo, hi) * u_ratio_footprint *
                   (mass > 0.0 ? weighted / mass : 0.0);
    } else
        seen.tau = v_seen_tau * weighted;
    for (int k = 0; k < kRatioPoints; ++k)
        ball[k] = weighted > 0.0 ? ball[k] / weighted : 0.0;
    seen.lit = cut_along + rank_lit_offset(a, b, seen.tau, ball, medium);
#else
    seen.tau = v_seen_tau * footprint_profile(x) * footprint_ray_share(x, v_depth_radius, lo, hi);
#endif
    return seen;
}

// The opacity of a ball's part seen along a ray, softened where it meets the terrain if asked.
float seen_alpha(Seen seen)
{
    float alpha = 1.0 - exp(-seen.tau);
    if (u_soft_edge > 0.0)  // a softer meeting with the terrain than the particle's own, if asked
        alpha *= clamp((seen.scene - seen.lit) / u_soft_edge, 0.0, 1.0);
    return alpha;
}

// The light the ball scatters towards the eye along `ray` (unit, from the eye), lit `t` along it.
vec3 ball_source(vec3 ray, float t)
{
    float log_gamma = 0.0;
    float sun_visible = v_grid_visible.w;
#ifdef KIRI_DENSITY_RATIO
    // The balls standing for the Medium are lit by its light, as the layers and the froxels are:
    // the Medium's optical depth towards the sun (the sun volume) and the terrain's shadow at the
    // lit point, not the attenuation buffer of the balls (a lumpy copy of the Medium's) and the
    // shadow at the ball's centre (docs/particles.md, "A still's particles at each sample").
    vec3 world = u_eye + ray * t;
    if (u_lit != 0) {
        bool covered = u_md_on != 0 && world.z < u_md_ceiling && shell_covers(world.xy);
        log_gamma = -medium_sun_optical_depth_in(world, u_sv_direction, 0.5, covered,
                                                 covered ? shell_column(world.xy) : vec4(0.0));
    }
    sun_visible = terrain_visibility(world, u_ts_bias);
#else
    vec3 relative = u_eye - u_centre + ray * t;
    if (u_lit != 0) {
        Ball ball = Ball(u_eye - u_centre + v_centre, v_optics, v_floor_plane, v_top_plane);
        log_gamma = billboard_log_gamma(u_log_gamma, grid_of(relative), v_grid_visible.xyz, v_window, v_table, ball,
                                        own_share_at(relative, ball.centre, v_optics.x, v_top_plane, v_own_share));
    }
#endif
    vec3 radiance = particle_radiance(log_gamma, dot(ray, u_sun_direction), v_optics.z, sun_visible);
    // The baked multiple scattering, not hidden by the terrain's shadow: the particle's, at the
    // lit point's height (particle_baked.comp).
    float baked = clamp(v_baked + v_baked_slope.x * (ray.z * t - v_centre.z), v_baked_slope.y, v_baked_slope.z);
#ifdef KIRI_BAKED_PER_FRAGMENT
    // A ball around the eye spans every direction and the whole depth of its fog: the volume is
    // read at each fragment's lit point (outside the shell, where it holds nothing, as above).
    float here = lv_in_scattered_at(u_eye + ray * t, -ray, u_anisotropy, false);
    baked = here > 0.0 ? here : baked;
#endif
    radiance += clamp(v_optics.z, 0.0, 1.0) * baked * u_sun_radiance;
    float haze = 1.0 - exp(-t * u_haze_density);
    radiance = mix(radiance, u_sky_horizon, haze);
    // The froxel fog in front of this billboard (read at its corners, particles.vert), as the
    // layers read it: over the already fogged frame, T C + a S composes to S + T (...).
    return radiance * v_fog.a + v_fog.rgb;
}

#ifdef PARTICLES_AT_SAMPLES
// The ray through sample s of this fragment's pixel (the frame's own target: depth_samples.glsl's
// offsets).
vec3 sample_ray(int s)
{
    vec2 ndc = (gl_FragCoord.xy + u_offsets[s]) / vec2(textureSize(u_depth, 0)) * 2.0 - 1.0;
    return normalize(u_camera_forward + ndc.x * u_tan_half.x * u_camera_right + ndc.y * u_tan_half.y * u_camera_up);
}
#endif

void main()
{
    vec3 ray = normalize(v_ray);
    bool widened = v_footprint_radius > v_depth_radius * 1.001;
    ivec2 depth_size = textureSize(u_depth, 0);
    ivec2 depth_pixel = widened ? clamp(ivec2((v_centre_ndc * 0.5 + 0.5) * vec2(depth_size)), ivec2(0), depth_size - 1)
                                : ivec2(gl_FragCoord.xy * u_depth_scale);
    float ground = view_depth(texelFetch(u_depth, depth_pixel, 0).r, u_near, u_far);
    float own_ground = widened ? view_depth(texelFetch(u_depth, ivec2(gl_FragCoord.xy * u_depth_scale), 0).r, u_near, u_far)
                               : ground;
#ifdef PARTICLES_AT_SAMPLES
    // A still drawn at the frame's resolution: the ball along each of the pixel's samples' rays,
    // each to its own ground and lit where it passes, each sample's blend in a target of its own
    // (docs/particles.md, "A still's particles at each sample"). R along each sample's own chord:
    // the Medium's detail changes within metres of height, and twelve points a pixel draw it
    // closer to its mean along the rays than three.
    Seen seen[4];
    vec3 rays[4];
    float alphas[4];
    float alpha = 0.0;
    for (int s = 0; s < 4; ++s) {
        rays[s] = sample_ray(s);
        float sample_ground = view_depth(texelFetch(u_samples_depth, ivec2(gl_FragCoord.xy), s).r, u_near, u_far);
        seen[s] = seen_along(rays[s], widened, widened ? ground : sample_ground, sample_ground);
        alphas[s] = seen_alpha(seen[s]);
        alpha = max(alpha, alphas[s]);
    }
    if (alpha < 1e-5)
        discard;
    vec4 blends[4];
    for (int s = 0; s < 4; ++s)
        blends[s] = alphas[s] < 1e-5 ? vec4(0.0) : vec4(ball_source(seen[s].lit_ray, seen[s].lit) * alphas[s], alphas[s]);
    o_color = blends[0];
    o_sample1 = blends[1];
    o_sample2 = blends[2];
    o_sample3 = blends[3];
#else
    Seen seen = seen_along(ray, widened, ground, own_ground);
    float alpha = seen_alpha(seen);
    if (alpha < 1e-5)
        discard;
    o_color = vec4(ball_source(seen.lit_ray, seen.lit) * alpha, alpha);
#endif
}
