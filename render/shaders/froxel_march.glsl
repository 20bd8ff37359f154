// Library (after froxel_apply.glsl and froxel_light.glsl): the fog-aware apply for the terrain
// and the sky (froxel_pixels.comp, froxel_upsample.comp, froxel_classify.comp).
//
// Where the volume's slices resolve the fog around a pixel (froxel_classify.comp,
// froxel_resolved) the volume's lookup (froxel_fog_at); elsewhere (froxel_marched_fog) the
// pixel's own ray is integrated over its own stretch of the Medium's shell (the shell's entry and
// exit rasterised at full resolution, cut at the pixel's depth) with the Medium's exact density
// and the height fog's closed-form optical depth, both lit at the ray's own points
// (froxel_light.glsl): thin layers and narrow valleys smaller than a tile keep their shape and
// their light, and so does a height fog tens of metres deep.

// FROXEL_HEIGHT_FOG 0: the variant for scenes without one (its code, never run, made the apply
// 1.7 times as slow on llvmpipe).
#ifndef FROXEL_HEIGHT_FOG
#define FROXEL_HEIGHT_FOG 1
#endif

uniform int u_fx_shell;               // the shell's per-pixel depths are there (eye outside it)
uniform int u_fx_pixel_steps;
// A march lights its ray at every fourth step's end, linear in between, unless the sun's share
// of the light at two such ends differs by more than this part of the larger: then at each step's
// ends (a ray entering a dense fog's sunlit top at a grazing angle, froxel_march). At 0.2 as
// close to the reference on the views bench, and the default still's marches took 8-13 % longer
// instead of 2-3 %.
const float froxel_refine_light = 0.4;
// Nor where the optical depths towards the sun at two such ends differ by more than this: the
// light of a dense fog's skin along rays grazing its top is curved in tau_sun between ends whose
// shares differ less (the bundled lake at 10 m of visibility: 3.25 % off the reference with
// the share's test alone, 1.73 % with this too, as with every step lit).
const float froxel_refine_tau = 1.0;
// Between lit points whose optical depths towards the sun differ by less than this the sun's
// share is drawn linear (the model's curve over a quarter of an optical depth is nearly a chord).
const float froxel_light_tau = 0.25;
uniform float u_fx_near;              // the volume's first depth
// Per pixel: minus the shell's nearest depth (-3e38: none) and its farthest (0: none).
uniform sampler2D u_fx_shell_depths;
uniform int u_fx_classified;          // the tiles' w marks where pixels march (froxel_classify.comp)

// The Medium's optical depth over the step [q0, q1] of length `len`: its extinction at the
// quarter points of the part of the step between the floor and the top of its column there, times
// that part's length. Taken at the step's middle alone, the step that straddles the fog's top or
// floor held all of its fog or none, at a depth that steps from pixel to pixel: from inside the
// fog the terrain's contours showed through as lines. Taken at the part's middle alone, steps
// tens of metres long across a ground the detail noise varies on every 47 m (the default tile's
// texel) aliased it into bands along the fog's top seen at a grazing angle (the descent just
// above the blanket, 320x180: 2.09 % off the reference; 1.08 % at two points, 1.27 % at one
// point in 32 steps instead of 24).
float froxel_step_depth(vec3 q0, vec3 q1, float len)
{
    vec3 middle = 0.5 * (q0 + q1);
    if (u_md_on == 0 || !shell_covers(middle.xy))
        return 0.0;
    vec4 c = shell_column(middle.xy);  // floor, bottom, top, coverage
    // One lookup of the column for both points: the part's ends were cut by it (its points lie
    // within half a step of the step's middle across).
    float lo = 0.0, hi = 1.0;
    float rise = q1.z - q0.z;
    if (abs(rise) > 1e-3 && c.z > c.x) {
        float t0 = clamp((c.x - q0.z) / rise, 0.0, 1.0), t1 = clamp((c.z - q0.z) / rise, 0.0, 1.0);
        lo = min(t0, t1);
        hi = max(t0, t1);
        if (!(hi > lo))
            return 0.0;
    }
    float sigma = froxel_sigma_in(mix(q0, q1, mix(lo, hi, 0.25)), c) + froxel_sigma_in(mix(q0, q1, mix(lo, hi, 0.75)), c);
    return 0.5 * sigma * len * (hi - lo);
}

// Adds the stretch [a, b] of the ray through uv (view depths) to fog = (radiance, T), in n steps
// spread like the slices over [a, b], up to `stop` (<= b: where the ray ends). The Medium (when
// with_medium): its optical depth over each step (froxel_step_depth), lit at the ray's own
// points every fourth step (medium_light_parts_at, froxel_light.glsl), in between linear, or at
// each step where the light of four differs by more than froxel_refine_light (the light of a
// dense fog's sunlit top falls severalfold across four steps of a grazing ray: the bundled lake
// from afar 2.07 % off the reference, 1.78 % so), the
// terrain's visibility of the sun taken along each step (segment_visibility); the froxels' J,
// bilinear across four tiles, mixed the light of a sunlit ridge and of a valley in its shadow
// (the lake's threads from afar 7.8 % off the reference so, 4.7 % lit at their own points). The
// height fog: its optical depth over each step in closed form, lit at its own points (the volume's J would light a haze a few
// tens of metres deep at one point of a slice hundreds of metres deep: the plain under the
// default scene's haze was 20 % too dark from above).
void froxel_march(inout vec4 fog, inout HazeRuns h, vec2 uv, float a, float b, int n,
                  bool with_medium, float stop)
{
    if (!(b > a) || n < 1)
        return;
    vec3 ray = fx_ray(uv);
    float stretch = length(ray);
    float d0 = a;
    vec4 j0 = vec4(0.0), j1 = j0;  // J's two parts (medium_light_parts_at) at the ends of four steps
    vec4 js0 = j0, js1 = j0;       // and at the ends of the step, where the four are refined
    float t0 = 0.0, t1 = 0.0, ts0 = 0.0, ts1 = 0.0;  // their optical depths towards the sun
    if (with_medium)
        j1 = medium_light_parts_at(u_fx_eye + ray * a, u_fx_eye, 0.5, t1);
    bool refined = false;
    float visible_d0 = -1.0;       // the terrain's visibility of the sun at d0 where the step before took it
    // Each pass lights one point and takes the steps that point completes: the end of the next
    // four steps (all four, unless the sun's share changes by more than froxel_refine_light over
    // them), or in four so refined the end of the next step (that step, and the four's last,
    // which ends where they do). llvmpipe runs a branch's code whether any lane takes it or not,
    // and a loop's body at least once: the light called in each step, for the ends of four, ran
    // in every step (the marches took 30 % longer).
    int k = 0, group_end = 0;  // the next step, the end of its four
    while (k < n && d0 < stop) {
        bool group_start = k == group_end;
        if (with_medium) {
            if (group_start)
                group_end = min(k + 4, n);
            float at = min(fx_slice_depth(float(group_start ? group_end : k + 1) / float(n), vec2(a, b)), stop);
            float t;
            vec4 j = medium_light_parts_at(u_fx_eye + ray * at, u_fx_eye, 0.5, t);
            if (group_start) {
                j0 = j1;
                j1 = j;
                t0 = t1;
                t1 = t;
                refined = abs(j1.a - j0.a) > froxel_refine_light * max(j0.a, j1.a) || abs(t1 - t0) > froxel_refine_tau;
                js0 = j0;
                ts0 = t0;
            } else {
                js1 = j;
                ts1 = t;
            }
        } else {
            group_end = n;
        }
        int last = !refined ? group_end : (group_start ? (group_end == k + 1 ? group_end : k)
                                                        : (k + 2 == group_end ? group_end : k + 1));
        for (; k < last && d0 < stop; ++k) {
            float d1 = min(fx_slice_depth(float(k + 1) / float(n), vec2(a, b)), stop);
            if (refined && k + 1 == group_end) {
                js1 = j1;  // the step ends where the four do
                ts1 = t1;
            }
            vec3 q0 = u_fx_eye + ray * d0, q1 = u_fx_eye + ray * d1;
#if FROXEL_HEIGHT_FOG
            float haze = height_fog_segment(q0, q1);
#else
            const float haze = 0.0;
#endif
            float medium = with_medium ? froxel_step_depth(q0, q1, (d1 - d0) * stretch) : 0.0;
            float visible_d1 = -1.0;
            if (haze + medium > 0.0) {
                float through = exp(-(haze + medium));
                float opacity = fog.a * (1.0 - through) / (haze + medium);  // per unit of optical depth
                if (medium > 0.0) {
                    float span = float(min(4, n - (k / 4) * 4));
                    vec4 parts = refined ? 0.5 * (js0 + js1) : mix(j0, j1, (float(k % 4) + 0.5) / span);
                    // Where tau_sun changes by more than froxel_light_tau between the lit points,
                    // the sun's share from tau_sun, which is linear between them (exact under a
                    // flat top), not the share drawn linear: the fitted model's rises over the
                    // first optical depth towards the sun and falls after it, and drawn linear
                    // between lit points four steps apart its hump was lost (a dense blanket from
                    // above 8 % too dark).
                    if (refined || abs(t1 - t0) > froxel_light_tau) {
                        vec2 tau = refined ? vec2(ts0, ts1)
                                           : mix(vec2(t0), vec2(t1), vec2(float(k % 4), float(k % 4 + 1)) / span);
                        float air = exp(-distance(0.5 * (q0 + q1), u_fx_eye) * u_air.w);
                        parts.a = sun_share_over_step(ray / stretch, air, tau.x, tau.y, haze + medium);
                    }
                    // The terrain's visibility of the sun along the step, not at the lit points.
                    float visible = parts.a > 0.0 ? segment_visibility(q0, q1, visible_d0, visible_d1) : 0.0;
                    fog.rgb += opacity * medium * medium_light_from_parts(parts, visible);
                }
#if FROXEL_HEIGHT_FOG
                if (haze > 0.0)
                    haze_run_step(h, opacity * haze, q0, q1, haze);
#endif
                fog.a *= through;
            }
            visible_d0 = visible_d1;
            d0 = d1;
            js0 = js1;
            ts0 = ts1;
        }
    }
}

// Pixel px's ray's entry into the Medium's shell and its exit (view depths; first 3e38 and last
// 0: none), rasterised. Only with the shell's per-pixel depths (u_fx_shell).
vec2 froxel_pixel_shell(ivec2 px)
{
    vec2 d = texelFetch(u_fx_shell_depths, px, 0).rg;
    return vec2(-d.x, d.y);
}

// The stretch [first, last] of view depths over which a ray (its surface at `end`, at most the
// volume's far depth) is in the Medium's shell (`shell`: froxel_pixel_shell's, or bounds of it),
// cut where the fog turns opaque (`cut`: the farthest end of the ranges of the tiles it reads,
// which end there: froxel_opaque.comp; 0: no cut) and where the froxels' share ends (combined
// mode); last <= first: none.
vec2 froxel_pixel_stretch(vec2 shell, float end, float cut)
{
    float first = max(shell.x, u_fx_near);
    float last = min(shell.y, end);
    if (!(u_hf.x > 0.0) && cut > first)  // without height fog the tiles' ranges end where the fog turns opaque
        last = min(last, cut);
    if (u_partitioned != 0)  // combined mode: the froxels' share ends at near_end from the eye
        last = min(last, u_partition.y);
    return vec2(first, last);
}

// The farthest end of the ranges of the four tiles the volume's lookup at uv reads (those with
// fog): where the fog along pixel uv's ray turns opaque (froxel_pixel_stretch's cut).
float froxel_pixel_cut(vec2 uv)
{
    vec2 p = uv * vec2(u_fx_size.xy) - 0.5;
    ivec2 base = ivec2(floor(p));
    float cut = 0.0;
    for (int k = 0; k < 4; ++k) {
        vec2 range = fx_tile_range(clamp(base + ivec2(k & 1, k >> 1), ivec2(0), u_fx_size.xy - 1));
        cut = range.y > range.x ? max(cut, range.y) : cut;
    }
    return cut;
}

// Whether the volume resolves the fog of pixel px (screen point uv, its surface at view depth
// `depth`): none of the four tiles its lookup reads was marked to march (froxel_classify.comp
// writes w), and those the lookup weighs (fog-aware: whose central ray reaches the pixel's
// depth, if any) have slices as deep as the pixel's fog goes, or are opaque by then (not so
// at a ground edge, where the tiles' ranges end at different grounds).
bool froxel_resolved(ivec2 px, vec2 uv, float depth)
{
    if (u_fx_classified == 0)
        return false;
    float end = min(depth, u_fx_far);
    float fog_end = end;  // where the pixel's fog ends: its surface, or where it leaves the shell
    if (u_fx_shell != 0 && !(u_hf.x > 0.0)) {
        vec2 shell = froxel_pixel_shell(px);
        fog_end = min(shell.y, end);
        if (!(fog_end > max(shell.x, u_fx_near)))
            fog_end = 0.0;
    }
    vec2 p = uv * vec2(u_fx_size.xy) - 0.5;
    vec2 f = p - floor(p);
    ivec2 base = ivec2(floor(p));
    bool aware = false, all_reach = true, aware_reach = true;
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        ivec2 tile = clamp(base + o, ivec2(0), u_fx_size.xy - 1);
        vec4 c = texelFetch(u_fx_tiles, tile, 0);
        if (c.w != 0.0)
            return false;
        float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        if (w <= 0.0 || fog_end <= 0.0)
            continue;
        bool deep = (c.y > c.x && c.y * 1.001 >= fog_end) ||
            texelFetch(u_fx_volume, ivec3(tile, u_fx_size.z - 1), 0).a < 1e-3;
        all_reach = all_reach && deep;
        if (c.z >= end * 0.999) {
            aware = true;
            aware_reach = aware_reach && deep;
        }
    }
    return aware ? aware_reach : all_reach;
}

// The fog in front of the surface at view depth `depth` (3e38: sky) seen through screen point uv
// (a pixel's centre, or a point of it), marched along its own ray where the volume does not
// resolve it: over its stretch of the shell (`shell`: froxel_pixel_shell(px), or bounds of the
// ray's own; or all of the ray where the fog is everywhere), the height fog over the rest. With
// `tiles_cut`, cut where the tiles the volume's lookup reads turn opaque (froxel_pixel_cut):
// their ranges follow the frame's resolved depths, which a split pixel's other side (a valley
// behind a ridge) lies beyond.
vec4 froxel_marched_fog(vec2 uv, float depth, vec2 shell, bool tiles_cut)
{
    float end = min(depth, u_fx_far);
    float near = u_fx_near;
    // The stretch of the Medium [first, last] (the ray's stop there), the height fog alone before
    // and after it. One call of the march for the Medium, whose steps and light are the costly
    // code: each copy of it inlined cost llvmpipe seconds of compiling on a new user's first
    // frame. Each call's own (with_medium a constant): in a loop over the stretches the march
    // took 40 % longer on llvmpipe.
    float first = near, last = u_fx_far, stop = end;
    int steps = u_fx_size.z;
    if (u_fx_shell != 0) {
        vec2 stretch = froxel_pixel_stretch(shell, end, tiles_cut ? froxel_pixel_cut(uv) : 0.0);
        first = stretch.x;
        last = stretch.y;
        stop = last;
        steps = u_fx_pixel_steps;
    }
    // Without the shell's depths the Medium may be anywhere along the ray (the eye in its
    // shell): its steps on one layout for every ray, the volume's slices to its far end, each
    // ray stopping at its surface. Spread over each ray's own length, the step straddling the
    // fog's top or floor lay differently in every pixel, and the terrain's contours showed
    // through the fog as bands (the descent from inside: 4.4 % off the reference, 1.5 % so).
    bool medium = last > first;
    vec4 fog = vec4(0.0, 0.0, 0.0, 1.0);
    HazeRuns h = haze_runs_along_ray();
#if FROXEL_HEIGHT_FOG
    // The height fog alone: before the Medium's stretch, or all the way where the ray misses it.
    bool haze = u_hf.x > 0.0 && u_fx_shell != 0;
    int haze_steps = max(u_fx_pixel_steps / 2, 1);
    if (haze)
        froxel_march(fog, h, uv, near, medium ? first : end, haze_steps, false, medium ? first : end);
#endif
    if (medium)
        froxel_march(fog, h, uv, first, last, steps, true, stop);
#if FROXEL_HEIGHT_FOG
    if (haze && medium)
        froxel_march(fog, h, uv, last, end, haze_steps, false, end);
    haze_runs_finish(h, fog.rgb);
#endif
    return fog;
}
