#version 450 core
// Terrain: coloured by ground.glsl (height, slope, water), lit by the sun and a hemispherical
// sky, hazed with distance towards the horizon colour so that far ridges read as far. The sun
// comes through the fog above: the ground under it lies in its shade.
in vec3 v_world;
in vec3 v_normal;
in vec4 v_shade;  // the fog's tau_sun (the Medium's, below 0 beyond its shade), whether to refine it, the height fog's (GroundShade)
uniform vec3 u_eye;
uniform vec3 u_sun_direction;  // towards the sun, unit
uniform vec3 u_sun_radiance;
uniform vec3 u_ambient;
uniform vec3 u_sky_horizon;
uniform float u_haze_density;  // 1/m
#ifdef SEEN_SAMPLES
layout(early_fragment_tests) in;
layout(post_depth_coverage) in;
#endif
// Per set of the pixel's samples (a bit each, 4 samples a pixel; else all zero: the centre) the
// mean of their offsets from the pixel's centre (pixels, window space).
uniform vec2 u_shown_offsets[16];
// The direction of the ray through window point q: u_rays[0] + q.x u_rays[1] + q.y u_rays[2].
uniform vec3 u_rays[3];
out vec4 o_color;  // linear radiance (tonemap.frag makes it a colour)
// FOG_SHADE_SAMPLES 1: the variant for a frame with the fog's shade (fog_sun_through).
#ifndef FOG_SHADE_SAMPLES
#define FOG_SHADE_SAMPLES 0
#endif

// Multisampling shades a triangle once a pixel at the pixel's centre, also where the triangle
// covers some of the pixel's samples but not the centre: there its inputs are extrapolated along
// its plane, hundreds of metres beyond its edge where it is seen at a grazing angle (a ridge's
// crest seen against the fogged valley behind it took the valley's shade, a third of its
// sunlight). The fragment is shaded at the mean of the samples it shows instead: with post-depth
// coverage those that passed the depth test (ground drawn earlier in front of it hides the
// rest), else those it covers. Not `centroid`: where that puts the point is the driver's choice,
// and llvmpipe's took the jacksboro_wind view from 1.95 to 2.63 % off the reference.
vec2 shown_offset() { return u_shown_offsets[gl_SampleMaskIn[0] & 15]; }

// The point of this fragment's triangle seen at window point q, and the inputs there: where the
// ray through q meets the triangle's plane (through v_world, spanned by its chords across the
// pixel's quad, exact on a plane), each input linear along the chords. Not interpolateAtOffset:
// llvmpipe extrapolates it linearly in the window, and a triangle seen at a grazing angle is far
// from linear there (a point 0.9 pixels from the sample it was asked for, 100 m along a valley's
// slope from 14 km away).
struct Shown {
    vec3 world, normal;
    vec4 shade;
};
Shown shown_at(vec2 q, vec3 wx, vec3 wy, vec3 nx, vec3 ny, vec4 sx, vec4 sy)
{
    Shown s = Shown(v_world, v_normal, v_shade);
    vec3 ray = u_rays[0] + q.x * u_rays[1] + q.y * u_rays[2];
    vec3 plane = cross(wx, wy);
    float facing = dot(ray, plane);
    float xx = dot(wx, wx), xy = dot(wx, wy), yy = dot(wy, wy), det = xx * yy - xy * xy;
    if (!(abs(facing) > 1e-6 * length(ray) * length(plane)) || !(det > 1e-12 * xx * yy))
        return s;  // seen edge-on, or no chords: the centre's
    vec3 p = u_eye + ray * (dot(v_world - u_eye, plane) / facing);
    vec3 d = p - v_world;
    float a = (yy * dot(wx, d) - xy * dot(wy, d)) / det, b = (xx * dot(wy, d) - xy * dot(wx, d)) / det;
    if (!(abs(a) < 64.0 && abs(b) < 64.0))
        return s;
    // The point along the chords too (p, within rounding): a plain's height stays exactly its own.
    return Shown(v_world + a * wx + b * wy, v_normal + a * nx + b * ny, v_shade + a * sx + b * sy);
}

// The share of the sun the fog lets through onto the ground the fragment shows, its tau_sun
// (ground_shade.glsl: the Medium's part, below 0 beyond its shade, and the height fog's) at the
// point it is shaded at, `at` from the pixel's centre. Where the fragment shows more than one
// sample, tau at each (along its derivatives across the pixel) weighed by how much of that
// sample's ground shows through the fog over it, e^-tau sin(sun) / sin(eye) as under a fog's
// flat top: the fragment's one colour is seen through each sample's fog, and across a dense
// fog's shore the sunlit ground beside it is what the pixel shows. The share at the point alone
// put the pixel's shade on that ground too (the bundled lake at 10 m of visibility, its first
// camera: 81 of 8,056 pixels more than 10 % off the reference, the split pixels' samples each
// lit as the reference lights them; 52 so). Each sample's own point on the triangle (shown_at)
// and its own lookup: 40, for four times the cost (the terrain pass in fog at 1280x720 320-340 ->
// 490-530 ms; so 340-390 ms).
float fog_sun_through(vec2 tau, vec2 at, vec3 world)
{
    float through = exp(-max(tau.x, 0.0) - tau.y);
#if FOG_SHADE_SAMPLES
    vec2 tx = dFdx(tau), ty = dFdy(tau);
    int shown = gl_SampleMaskIn[0] & 15;
    float lit = 0.0, weights = 0.0;
    float rise = max(u_sun_direction.z, 0.0) / max(normalize(u_eye - world).z, 0.05);
    for (int i = 0; i < 4; ++i) {
        vec2 d = u_shown_offsets[1 << i] - at;
        vec2 t = max(tau + d.x * tx + d.y * ty, 0.0);
        float share = (shown & (1 << i)) != 0 ? exp(-t.x - t.y) : 0.0;
        float w = share > 0.0 ? exp(-(t.x + t.y) * rise) : 0.0;
        lit += w * share;
        weights += w;
    }
    if (bitCount(shown) > 1 && weights > 1e-6)
        through = lit / weights;
#endif
    return through;
}

void main()
{
    // The chords first, in uniform control flow.
    vec3 wx = dFdx(v_world), wy = dFdy(v_world), nx = dFdx(v_normal), ny = dFdy(v_normal);
    vec4 sx = dFdx(v_shade), sy = dFdy(v_shade);
    vec2 at = shown_offset();
    Shown seen = at == vec2(0.0) ? Shown(v_world, v_normal, v_shade)
                                 : shown_at(gl_FragCoord.xy + at, wx, wy, nx, ny, sx, sy);
    vec3 world = seen.world;
    vec3 n = normalize(seen.normal);
    vec4 shade = seen.shade;
    vec3 base = ground_albedo(world, n.z);
    float direct = max(dot(n, u_sun_direction), 0.0);
    // The fog's shade, in uniform control flow (its derivatives across the pixel).
    float through = fog_sun_through(ground_sun_depths(world, shade), at, world);
    // The terrain's own shadow where the froxel fog built the sun's shadow map (terrain_shadow.glsl;
    // froxel_none.glsl without it), and the fog's shade (ground_shade.glsl).
    if (direct > 0.0)
        direct *= terrain_shadow(world, n, u_sun_direction) * through;
    vec3 sky = u_ambient * (0.6 + 0.4 * n.z);
    vec3 radiance = base * (u_sun_radiance * direct + sky);
    float haze = 1.0 - exp(-length(world - u_eye) * u_haze_density);
    radiance = mix(radiance, u_sky_horizon, haze);
    o_color = vec4(radiance, 1.0);
}
