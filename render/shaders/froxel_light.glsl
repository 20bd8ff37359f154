// Library (after fog_lighting.glsl, medium_shell.glsl, froxel_medium.glsl, sun_march.glsl,
// sun_volume.glsl, terrain_shadow.glsl and light_volume.glsl): each medium's lighting at a point
// (geometry/fog_lighting.hpp, docs/froxel.md), as the froxels' lighting pass lights a froxel
// and as the apply lights the height fog along a pixel's own ray. S = albedo sigma (E_sun V P +
// L_amb) per medium, V the terrain's visibility of the sun (terrain_shadow.glsl), P the sun's
// phase through tau_sun (sun_volume.glsl) over the scattering octaves, plus the baked multiple
// scattering (light_volume.glsl, the Medium's model `baked` only).
uniform vec3 u_sun_direction;
uniform vec3 u_sun_radiance;
uniform vec3 u_ambient;
uniform vec4 u_air;         // the air's radiance (rgb) and extinction (1/m; 0: none)
uniform vec2 u_albedo;      // medium, height fog
uniform vec2 u_anisotropy;  // medium, height fog
uniform int u_fog_shadows;
uniform int u_octaves;      // 1: single scattering

// The height fog's light is followed in pieces of at most this optical depth (at most this many).
const float froxel_haze_piece_depth = 0.25;
const int froxel_haze_pieces = 16;
// A step or froxel whose height fog adds less than this share of what the eye sees
// (T (1 - exp(-tau))) takes the height fog's light lit nearest along its ray (HazeRuns): a ray
// through the haze's thin top, tens of steps of it, would pay the whole lighting at each.
const float froxel_haze_significant = 1e-2;

// The sun's share of J of medium m along `ray` through tau_sun of optical depth, per unit of the
// sun's radiance as the terrain lets it through (J = J_shade + V sun_colour s, V that visibility).
float medium_sun_share(int m, vec3 ray, float tau)
{
    return sun_scattering(dot(ray, u_sun_direction), u_anisotropy[m], u_albedo[m], tau,
                          normalize(u_sun_direction).z, u_octaves);
}

// J's growth per unit of the sun's share and of the terrain's visibility of the sun, medium m,
// before the air: pi sun (fog_lighting.hpp) scattered with the medium's albedo.
vec3 medium_sun_colour(int m) { return 3.14159265358979 * u_sun_radiance * u_albedo[m]; }

// J of medium m (0: the Medium, 1: the height fog) at p, seen along `ray` (unit, from the eye),
// with the sun's visibility and optical depth there: the in-scattered radiance per unit of that
// medium's extinction, before the air.
vec3 medium_light(int m, vec3 p, vec3 ray, float visible, float tau)
{
    vec3 s = u_albedo[m] * u_ambient;
    if (visible > 0.0)
        s += medium_sun_colour(m) * (visible * medium_sun_share(m, ray, tau));
    // The baked light scattered at least once towards the eye, inside the Medium's shell, not
    // hidden by the terrain's shadow (it reaches the shadow from the sunlit fog beside it).
    if (u_lv_on != 0)
        s += u_sun_radiance * u_albedo[m] * lv_in_scattered_at(p, -ray, u_anisotropy[m], false);
    return s;
}

// J as seen from `eye` through the air (geometry/air_light.hpp): mixed towards the horizon's
// colour by the distance, as the layers, the particles, the terrain and the reference see theirs.
vec3 through_air(vec3 j, vec3 p, vec3 eye) { return mix(j, u_air.rgb, 1.0 - exp(-distance(p, eye) * u_air.w)); }

// The point whose light a point p of the Medium takes. J is the light of fog: a point above the
// fog's top or below its bottom (a tile's jittered point above the fog its central ray is in, a
// froxel without fog whose J the apply reads for fog nearby, a march's point between the fog's
// top and the ground) would take the sun's light in empty air, unshadowed by the fog, under a
// grazing sun all of the difference; it takes the light of its column's fog nearest to it, a
// thousandth of the fog's depth inside its floor (the baked light ends at the column's floor,
// where a ray's last point lies on the ground) and at most a millimetre under its top (the sunlit
// skin of a dense fog is decimetres deep: at 10 per metre, a third of a metre under a 300 m
// fog's top the sun is down to e^-6).
// With p's column at hand (shell_column(p.xy), read where `covered`: shell_covers(p.xy)).
vec3 medium_lit_point_in(vec3 p, bool covered, vec4 column)  // column: floor, bottom, top, coverage
{
    vec3 lit = p;
    float lo = max(column.x, column.y), hi = column.z;
    if (covered && hi > lo)
        lit.z = clamp(p.z, mix(lo, hi, 1e-3), hi - min(1e-3 * (hi - lo), 1e-3));
    return lit;
}
vec3 medium_lit_point(vec3 p)
{
    bool covered = shell_covers(p.xy);
    return medium_lit_point_in(p, covered, covered ? shell_column(p.xy) : vec4(0.0));
}

// The Medium's J at p seen from the eye in two parts, as the froxels' lighting pass stores it and
// the pixels' marches take it at their points: (J in the terrain's shadow, the sun's share s seen
// through the air), J = J_shade + V s medium_sun_colour(0) for the terrain's visibility V of the
// sun (medium_light_from_parts). Where the fog is, V is taken along each ray through a slice or a
// step (segment_visibility): one point's V for a slice tens of metres deep left bands along the
// shade a canyon's wall casts into its fog. sun_jitter: where along its steps the sun's optical
// depth is marched.
// tau: the optical depth towards the sun there.
vec4 medium_light_parts_at(vec3 p, vec3 eye, float sun_jitter, out float tau)
{
    // p's column read once, for its lit point and its optical depth towards the sun.
    bool covered = shell_covers(p.xy);
    vec4 column = covered ? shell_column(p.xy) : vec4(0.0);
    vec3 lit = medium_lit_point_in(p, covered, column), ray = normalize(p - eye);
    tau = u_fog_shadows != 0 ? sun_optical_depth_in(lit, u_sun_direction, sun_jitter, covered, column) : 0.0;
    float air = exp(-distance(p, eye) * u_air.w);  // J's own share against the air's (through_air)
    return vec4(mix(u_air.rgb, medium_light(0, lit, ray, 0.0, tau), air), air * medium_sun_share(0, ray, tau));
}

vec4 medium_light_parts_at(vec3 p, vec3 eye, float sun_jitter)
{
    float tau;
    return medium_light_parts_at(p, eye, sun_jitter, tau);
}

// The mean over a step of the sun's share of the Medium's J along `ray` (medium_sun_share, times
// `air`, J's own share against the air's), weighted by what the step lets through in front of
// each point: e^(-depth u) at u in [0, 1] along it, depth its optical depth, the optical depth
// towards the sun linear from tau0 to tau1 along it (exact under a flat top). Across a dense
// fog's sunlit skin, decimetres deep under steps of metres, the share at the step's middle or
// the mean of its ends is far off. No model's share falls faster than single scattering's
// e^-tau_sun, so the share times e^(rise u) (rise: tau_sun's gain over the step) is smooth, and
// is integrated against e^(-(depth + rise) u) by that weight's two-point Gauss rule
// (exp_weight_gauss_rule, fog_lighting.glsl): single scattering exactly, the skin under a flat
// top s / (1 + the view's rate of descent over the sun's). Where tau_sun changes by no more than
// 0.1 over the step, the share at its middle. One call of the share a pass of one loop, the
// rule's two nodes or the middle: llvmpipe runs a branch's code whether any lane takes it or not,
// so the middle's own call ran in every step too.
float sun_share_over_step(vec3 ray, float air, float tau0, float tau1, float depth)
{
    bool nodes = abs(tau1 - tau0) > 0.1;
    float rise = max(tau1 - tau0, 0.0);
    vec2 u, w;
    exp_weight_gauss_rule(depth + rise, u, w);
    float mean = 0.0;
    for (int i = 0; i < (nodes ? 2 : 1); ++i) {
        float share = medium_sun_share(0, ray, nodes ? mix(tau0, tau1, u[i]) : 0.5 * (tau0 + tau1));
        mean += nodes ? w[i] * share * exp(rise * u[i]) : share;
    }
    return nodes ? air * mean * fog_exp_mean(depth + rise) / fog_exp_mean(depth) : air * mean;
}

// The terrain's visibility of the sun for the Medium's light at p (medium_lit_point).
float medium_visibility_at(vec3 p) { return terrain_visibility(medium_lit_point(p), u_ts_bias); }

// Its mean over the segment [a, b] of a ray, given its value at a (va, or < 0: not taken yet; vb:
// its value at b, the next segment's va): the ends' mean where they agree, else the middles' of
// eight pieces: the edge of the shade a wall casts into the fog crosses the segment there. One
// point's visibility for a slice or four steps of a march tens of metres deep left bands along
// that shade a slice or four steps apart (the views bench's canyon from inside its fog: the
// froxels 2.37 % off the reference, 0.72 % now; 0.71 % with 256 slices instead of 64). One
// lookup a pass of one loop, b's, a's where not taken, then the middles where the ends differ:
// llvmpipe runs a branch's code whether any lane takes it or not and a loop's body at least
// once, so written as three lookups and a loop of eight, each step of a march took three.
float segment_visibility(vec3 a, vec3 b, float va, out float vb)
{
    int ends = va >= 0.0 ? 1 : 2, count = ends;
    float sum = 0.0;
    vb = 0.0;
    for (int p = 0; p < count; ++p) {
        float v = medium_visibility_at(p == 0 ? b : (p < ends ? a : mix(a, b, (float(p - ends) + 0.5) / 8.0)));
        vb = p == 0 ? v : vb;
        va = p > 0 && p < ends ? v : va;
        sum += p >= ends ? v : 0.0;
        if (p == ends - 1 && !(abs(va - vb) < 0.02))
            count = ends + 8;
    }
    return count == ends ? 0.5 * (va + vb) : sum / 8.0;
}

// J from its two parts (medium_light_parts_at), the terrain's visibility of the sun being `visible`.
vec3 medium_light_from_parts(vec4 parts, float visible) { return parts.rgb + (visible * parts.a) * medium_sun_colour(0); }

// The height fog's J at p, seen from the eye, with the terrain's visibility of the sun and the
// Medium's optical depth towards it there (both change over hundreds of metres, the height fog's
// own optical depth over tens: added here in closed form).
vec3 height_fog_light_with(vec3 p, vec3 eye, float visible, float medium_tau)
{
    float tau = u_fog_shadows != 0 && visible > 0.0 ? medium_tau + height_fog_sun(p, u_sun_direction) : 0.0;
    return through_air(medium_light(1, p, normalize(p - eye), visible, tau), p, eye);
}

// The height fog's J at p, seen from the eye: its visibility and tau_sun at p itself. The height
// fog is a closed form, so its light is too wherever its optical depth changes faster than a
// froxel or a march step can follow (tens of metres under a grazing sun).
// The height fog along the segment [a, b] (in it, `tau` of its optical depth): its in-scattered
// radiance per unit of opacity as the eye at a's side sees it, each of n pieces' light weighted
// by the light the pieces in front of it let through. The pieces split the part of the segment
// below 8 scale heights over the base (geometry::HeightFog::top, the slices' top for it too),
// where all but e^-8 of the haze is (a step of a march
// from afar is a kilometre long, its haze in its last hundred metres), and share the terrain's
// visibility of the sun and the Medium's optical depth towards it, taken at that part's middle.
vec3 height_fog_segment_light(vec3 a, vec3 b, vec3 eye, float tau)
{
    float cap = u_hf.y + 8.0 * u_hf.z, rise = b.z - a.z;
    float t0 = 0.0, t1 = 1.0;
    if (abs(rise) > 1e-6) {
        float at_cap = (cap - a.z) / rise;
        if (rise > 0.0)
            t1 = clamp(at_cap, 0.0, 1.0);
        else
            t0 = clamp(at_cap, 0.0, 1.0);
    }
    if (!(t1 > t0)) {  // all of it above the cap
        t0 = 0.0;
        t1 = 1.0;
    }
    vec3 lo = mix(a, b, t0), hi = mix(a, b, t1);
    int n = clamp(int(ceil(tau / froxel_haze_piece_depth)), 1, froxel_haze_pieces);
    vec3 middle = 0.5 * (lo + hi);
    float visible = terrain_visibility(middle, u_ts_bias);
    float medium_tau = u_fog_shadows != 0 && visible > 0.0 ? medium_sun_optical_depth(middle, u_sun_direction, 0.5) : 0.0;
    // One call of the light, in a loop the compiler keeps (each copy of it inlined cost llvmpipe
    // a second of compiling each program that lights the height fog).
    vec3 sum = vec3(0.0), first = vec3(0.0);
    float weight = 0.0, through = 1.0;
    for (int i = 0; i < n && (i == 0 || through > 0.01); ++i) {  // what lies behind 99 % of it weighs little
        vec3 p0 = mix(lo, hi, float(i) / float(n)), p1 = mix(lo, hi, float(i + 1) / float(n));
        float piece = exp(-height_fog_segment(p0, p1)), opacity = through * (1.0 - piece);
        vec3 j = height_fog_light_with(0.5 * (p0 + p1), eye, visible, medium_tau);
        first = i == 0 ? j : first;
        sum += opacity * j;
        weight += opacity;
        through *= piece;
    }
    return weight > 0.0 ? sum / weight : first;
}

// The height fog's J at p, seen from the eye: its visibility and tau_sun at p itself (a segment
// of no length).
vec3 height_fog_light(vec3 p, vec3 eye) { return height_fog_segment_light(p, p, eye, 0.0); }

// The height fog's light along a ray, front to back in steps (the apply's march, the
// integration's froxels), lit once the steps are known: on a GPU's SIMD lanes a light taken at
// whichever step each ray needs it costs every lane each of those steps (the apply's march took
// 4.6 times as long so on llvmpipe). The steps that add more than froxel_haze_significant of
// what the eye sees (T (1 - exp(-tau_step)) tau / tau_step, over both media) must be lit; runs
// of them make one stretch each, lit as one segment (height_fog_segment_light: its pieces follow
// the light within it); at most haze_runs of them, a later run joins the last. Steps between runs
// take the light of the run before them (those before the first, of the first; with no run, of
// the heaviest of them, once they add up to 5 times froxel_haze_significant).
const int haze_runs = 2;  // haze_run_a and the rest index runs 0 and 1 by name: two, no more
struct HazeRuns {
    vec3 a[haze_runs], b[haze_runs];  // each run's ends
    float tau[haze_runs];             // its height fog's optical depth
    float share[haze_runs];           // what takes its light
    int count;
    bool open;                        // the last step was lit: the next one lit extends its run
    float before;                     // the share of the steps before the first run
    vec3 at;                          // the middle of the heaviest of those
    float heaviest;
};

HazeRuns haze_runs_along_ray()
{
    HazeRuns r;
    for (int i = 0; i < haze_runs; ++i) {
        r.a[i] = r.b[i] = vec3(0.0);
        r.tau[i] = r.share[i] = 0.0;
    }
    r.count = 0;
    r.open = false;
    r.before = r.heaviest = 0.0;
    r.at = vec3(0.0);
    return r;
}

// Run i's ends, optical depth and share, read and written at constant indices only: an array of
// the struct indexed by a variable (the run's count, a loop's counter) is kept in local memory by
// NVIDIA's compiler, and each step of each march read and wrote it there (docs/speed.md, "On a GPU").
vec3 haze_run_a(HazeRuns r, int i) { return i == 0 ? r.a[0] : r.a[1]; }
vec3 haze_run_b(HazeRuns r, int i) { return i == 0 ? r.b[0] : r.b[1]; }
float haze_run_tau(HazeRuns r, int i) { return i == 0 ? r.tau[0] : r.tau[1]; }
float haze_run_share(HazeRuns r, int i) { return i == 0 ? r.share[0] : r.share[1]; }

// Step [a, b] of the height fog's optical depth tau, whose light adds `share` of it. Written with
// selects, not branches: every step of every march runs it, and on llvmpipe's eight lanes in
// lockstep the branches cost more than the few additions they chose between.
void haze_run_step(inout HazeRuns r, float share, vec3 a, vec3 b, float tau)
{
    bool needs = share > froxel_haze_significant || (r.count == 0 && r.before + share > 5.0 * froxel_haze_significant);
    // A step that must be lit opens a run where the last step was not lit, while there are runs
    // to open; a later one joins the last run (the stretch between adds little).
    bool opens = needs && !r.open && r.count < haze_runs;
    bool first = opens && r.count == 0, second = opens && r.count == 1;
    r.a[0] = first ? a : r.a[0];
    r.share[0] = first ? r.before : r.share[0];
    r.a[1] = second ? a : r.a[1];
    r.count += opens ? 1 : 0;
    // The step's share goes to the last run, or before the first; a lit step also grows it.
    bool to0 = r.count == 1, to1 = r.count == 2;
    r.b[0] = needs && to0 ? b : r.b[0];
    r.b[1] = needs && to1 ? b : r.b[1];
    r.tau[0] += needs && to0 ? tau : 0.0;
    r.tau[1] += needs && to1 ? tau : 0.0;
    r.share[0] += to0 ? share : 0.0;
    r.share[1] += to1 ? share : 0.0;
    bool before = r.count == 0;
    r.before += before ? share : 0.0;
    bool heavier = before && share > r.heaviest;
    r.heaviest = heavier ? share : r.heaviest;
    r.at = heavier ? 0.5 * (a + b) : r.at;
    r.open = needs;
}

void haze_runs_finish(HazeRuns r, inout vec3 radiance)
{
    // Without a run, the heaviest step's light at its middle (a segment of no length); one call of
    // the light in a loop the compiler keeps.
    bool lone = r.count == 0;
    if (lone && !(r.before > 1e-5))
        return;
    for (int i = 0; i < max(r.count, 1); ++i)
        radiance += (lone ? r.before : haze_run_share(r, i)) *
            height_fog_segment_light(lone ? r.at : haze_run_a(r, i), lone ? r.at : haze_run_b(r, i), u_fx_eye,
                                     lone ? 0.0 : haze_run_tau(r, i));
}
