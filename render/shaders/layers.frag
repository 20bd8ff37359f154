#version 450 core
// A fog layer, in one of two shadings (geometry::LayerShading):
// - source: the atlas alpha (border fade) times the layer's alpha with the spacing correction
//   1 - (1 - a)^(r / r0), gray, lit by an ad hoc sun and sky term;
// - medium: the slab of fog the layer stands for (docs/medium.md): density = the layer's
//   profile x border fade x detail, optical depth sigma_t density r n_z / |cos(view, normal)|
//   (from the eye for the first layer a ray crosses; layers_end.frag adds what lies before the
//   terrain in a slab whose layer a ray never crosses),
//   the fog's lighting model (fog_lighting.glsl) with tau_sun from the sun volume
//   (sun_volume.glsl), in the terrain's shadow from the sun (terrain_shadow.glsl: the froxels'
//   and the reference's).
// Combined mode (fog_partition.glsl): the medium shading draws only the layers' share.
// Both: world-space detail noise drifting with the wind; where the layer meets the ground, the
// part of its slab before the ground along the ray, with the stretch pass, or above the ground
// under the layer (medium), or a soft fade (source). Output is premultiplied
// linear radiance.
in vec3 v_world;
in vec2 v_uv;
in float v_alpha;
in float v_exponent;
in float v_spacing;
in float v_slab;
in float v_slab_above;
in float v_height;
in vec3 v_normal;
in float v_baked;
flat in int v_layer;

uniform sampler2D u_atlas;
uniform sampler2D u_heights;     // terrain heights (world metres), R32F
uniform vec4 u_height_rect;      // x0, y0, 1 / extent x, 1 / extent y
uniform vec2 u_height_texels;    // nx, ny
uniform float u_opacity;
uniform float u_ground_fade;
uniform vec3 u_sky_horizon;
uniform float u_haze_density;
uniform int u_medium;            // 1: LayerShading::medium
uniform float u_extinction;      // sigma_t (1/m) at density 1
uniform float u_top_loss;        // 1 - top_density
uniform float u_thickness;       // T0 (m)
uniform float u_lv_per_fragment; // metres from the eye within which the baked light is per fragment
#ifndef LAYERS_BAKED_PER_FRAGMENT
#define LAYERS_BAKED_PER_FRAGMENT 1
#endif
uniform int u_md_extent;         // 1: the Medium's grid is bound (medium_shell.glsl), its coverage is where the fog is
uniform int u_sun_lookup;        // 1: tau_sun from the sun volume (sun_volume.glsl), at u_sv_direction
uniform vec3 u_sv_direction;
uniform int u_stretch_pass;      // 1: layers_end.frag draws the fog a ray crosses before the terrain in a slab whose
                                 // layer it never crosses; the frame's depth is bound (u_frame_depth)
uniform vec2 u_target_size;      // the target's pixels: a fragment's texel in u_frame_depth
out vec4 o_color;
#if defined(LAYERS_AT_SAMPLES)
// Drawn at the frame's resolution (LayersPass::draw_reduced at scale 1): each slab is taken along
// the rays of the pixel's samples, each to its own ground (layers_light.glsl), into a blend of the
// stack per sample, sample 0's in o_color. Where the fog changes across a pixel (a dense fog's
// shore: its first metres opaque, the shore line through the pixel), the pixel's centre holds
// other fog than its samples (docs/layers.md). The samples apart: a pixel across a ridge's
// silhouette with the fog behind it sees the stack at one sample only, and the mean of each
// layer's opacity over the samples, blended over 15 layers, made 0.94 of that sample's fog.
layout(location = 1) out vec4 o_sample1;
layout(location = 2) out vec4 o_sample2;
layout(location = 3) out vec4 o_sample3;
float sample_alpha[4];        // each sample's opacity of this layer's slab
vec3 sample_radiance[4];      // and the light it scatters towards the eye
#endif

// geometry::layer_slab_over_ground: of the layer's slab (share of r), the share above the ground.
float layer_slab_over_ground(float share, int i, float spacing, float clearance)
{
    if (!(clearance >= 0.0) || !(spacing > 0.0))
        return 0.0;
    if (clearance >= spacing || i == 0)  // the base has no fog under it
        return share;
    float lower = min(share, 0.5);  // the slab's half under the layer
    return clearance / spacing + (share - lower);
}

// The terrain's height under xy (u_heights: texel centres at the heightfield's samples).
float terrain_height(vec2 xy)
{
    vec2 uv = (xy - u_height_rect.xy) * u_height_rect.zw;
    return texture(u_heights, (uv * (u_height_texels - 1.0) + 0.5) / u_height_texels).r;
}

// The distance along this fragment's ray to the terrain, at the centre of its texel as
// layers_end.frag takes it (1e30: the sky).
float ground_distance()
{
    vec3 ground;
    return frame_ground(gl_FragCoord.xy / u_target_size, ground) ? distance(ground, u_eye) : 1e30;
}

// Whether this fragment is where its ray leaves the space around the eye: every ray from an eye
// inside the stack leaves the space between the two layers either side of it through one of them,
// upwards through the one over it or downwards through the one under it. That space is flat near
// the eye, and a ray at a grazing angle crosses its fog for hundreds of metres (up to the
// narrowing's flat radius and on) before it meets a layer. A ray that comes back into that space
// far off crosses the same layers again: within u_first_reach only.
bool leaves_the_eyes_slab(vec3 view, vec3 across, float dist)
{
    if (u_eye_inside == 0 || dist > u_first_reach)
        return false;
    float j = eye_region(view);
    float climb = dot(view, dot(across, v_normal) < 0.0 ? -across : across);
    return climb > 0.0 ? float(v_layer) == j + 1.0 : float(v_layer) == j;
}

#if defined(LAYERS_AT_SAMPLES)
// Where sample s's ray crosses this fragment's layer: the plane of its triangle (normal `plane`)
// through the centre's point. Moved along the screen's derivatives instead, a layer seen at a
// grazing angle (the ridge camera's, towards the horizon) put a sample's point far off its ray.
vec3 sample_point(int s, vec3 plane)
{
    vec3 ray = normalize(unproject(sample_uv(s), 1.0) - u_eye);
    float across = dot(ray, plane);
    if (!(abs(across) > 1e-6 * length(plane)))
        return v_world;
    return u_eye + ray * (dot(v_world - u_eye, plane) / across);
}
#endif

// The light a slab scatters towards the eye along `view`: it enters the slab `entry` from the eye
// and crosses `path` of it at extinction `sigma`, its layer `dist` from the eye at `point`; the
// Medium's column there (`covered`, `column`) as main read it.
vec3 slab_radiance(vec3 point, vec3 view, float entry, float path, float dist, float sigma, bool covered, vec4 column,
                   float coverage)
{
    float cos_sun = dot(view, u_sun_direction);
    vec3 radiance;
    // A slab seen at a grazing angle is many mean free paths long: the terrain's shadow is
    // taken over the light it scatters along its path (path_visibility), the baked light at
    // that light's centroid, not at the layer.
    // A slab crossed steeply is taken at the layer (one lookup: most fragments).
    int points = visibility_points(path, v_spacing);
    float sun_up = 0.0;
    if (u_sun_direction.z > 0.0)
        sun_up = points > 1 ? path_visibility(u_eye + view * entry, view, path, sigma * path, points)
                            : terrain_visibility(point, u_ts_bias);
    float tau_sun;
    if (u_sun_lookup != 0) {
        // The fog's optical depth towards the sun, as the froxels and the reference take it:
        // the whole Medium along the slanted path (its top and coverage over the columns the
        // path crosses, the detail), from the sun volume at this fragment, and the height fog.
        // Not interpolated from the base's vertices: a lake's base spans the ridges between its
        // threads, where a vertex lies in the ground, and a triangle across a thread's edge
        // mixed the thread's tau_sun with a point's inside the ridge (the lake's threads 7 %
        // too dark in the sun's light, docs/layers.md).
        if (u_md_extent == 0) {  // the column was not read above
            covered = u_md_on != 0 && shell_covers(point.xy);
            column = covered ? shell_column(point.xy) : vec4(0.0);
        }
        tau_sun = sun_optical_depth_in(point, u_sv_direction, 0.5, covered, column);
    } else {
        // No Medium given: the slab above this layer, the profile integrated from h to the
        // top, (1 - h) - k (1 - h^2) / 2 of the thickness, along the slant of the sun.
        float h = v_height;
        float above = u_extinction * coverage * u_thickness * ((1.0 - h) - 0.5 * u_top_loss * (1.0 - h * h));
        tau_sun = above / max(u_sun_direction.z, 0.02);
    }
    // tau_sun along the path as under a flat top: linear through its value at the layer,
    // from where the ray enters the slab to where it leaves. Where it changes by more than 1
    // across the slab (a dense fog's sunlit skin, at 0.4 per metre a few metres deep, in slabs
    // ten metres thick), S over the slab; thinner (the bundled lake's slabs: 0.8) S where the
    // path's light comes from, the centroid of what it scatters, is as close (the lake 5.23 ->
    // 5.19 % for 40 % more time in the layers pass): the middle of a thin slab, nearer the
    // eye along a path from it.
    float rate = -view.z * sigma / max(u_sun_direction.z, 0.05);  // tau_sun's change a metre along the ray
    if (abs(rate * path) > 1.0)
        radiance = fog_source_of(sun_scattering_over_slab(cos_sun, max(tau_sun - rate * (dist - entry), 0.0),
                                                          max(tau_sun + rate * (entry + path - dist), 0.0),
                                                          sigma * path),
                                 sun_up);
    else
        radiance = fog_source(cos_sun, max(tau_sun + rate * (entry + emission_centroid(path, sigma * path) - dist), 0.0),
                              sun_up);
    // The baked multiple scattering (light_volume.glsl; u_lv_on with the model `baked`),
    // towards the eye, not hidden by the terrain's shadow: from the vertices (layers.vert),
    // but near the eye, where a triangle spans a wide angle of directions towards it, per
    // fragment.
    // LAYERS_BAKED_PER_FRAGMENT 0: no layer comes that near the eye (LayersPass::stack_program).
    if (u_lv_on != 0)
        radiance += u_albedo * u_sun_radiance *
#if LAYERS_BAKED_PER_FRAGMENT
            (dist < u_lv_per_fragment
                 ? lv_in_scattered_at(u_eye + view * (entry + emission_centroid(path, sigma * path)), -view,
                                      u_anisotropy, true)
                 : v_baked);
#else
            v_baked;
#endif
    return radiance;
}

void main()
{
    // Both shadings' opacity is a product of v_alpha, the atlas's alpha and the ground fade:
    // where one is 0 the fragment adds nothing (and would be discarded below), so it stops
    // before its lighting. Most of a stack's fragments: the layers above a column's count
    // (faded in only near the eye, drawn for the whole stack), the atlas's border, the ground.
    if (v_alpha <= 0.0)
        discard;
    // Where the fog is, and how much of it (its border fade, in alpha): the medium shading draws the
    // Medium's own, its coverage and the wall at its grid's edge, as the reference and the froxels
    // see it; the atlas's border mask follows the base's patches, which reach past it (a fill's or
    // a lake's footprint is the fog's cells, not the patches), and the enlargement (2.10) carries
    // the layers further. The source shading, and the medium's without a Medium, take the atlas.
    vec4 tex;
    float thickness = 1e30;  // the fog's, for combined mode's particle share (fog_partition.glsl)
    bool covered = false;    // the Medium's column here, read once (its optical depth towards the sun reads it too)
    vec4 column = vec4(0.0);
    if (u_medium != 0 && u_md_extent != 0) {
        covered = shell_covers(v_world.xy);
        column = covered ? shell_column(v_world.xy) : vec4(0.0);
        tex = vec4(1.0, 1.0, 1.0, column.w);
        thickness = column.z - column.x;
    } else {
        tex = texture(u_atlas, v_uv);
    }
    if (tex.a <= 0.0)
        discard;
    float clearance = v_world.z - terrain_height(v_world.xy);
    // The medium shading: the part of this layer's slab above the ground, down to the ground where
    // the layer under it lies below the ground (hidden by the terrain), as a share of the slab;
    // with the stretch pass, the slab along the ray up to where the ray meets the ground (below).
    float ground;
    if (u_medium != 0 && u_stretch_pass != 0)
#if defined(LAYERS_AT_SAMPLES)
        ground = 1.0;  // the samples' own (below)
#else
        ground = clearance >= 0.0 ? 1.0 : 0.0;
#endif
    else if (u_medium != 0)
        ground = layer_slab_over_ground(v_slab, v_layer, v_spacing, clearance) / max(v_slab, 1e-6);
    else
        ground = u_ground_fade > 0.0 ? smoothstep(0.0, u_ground_fade, clearance) : step(0.0, clearance);
    // Combined mode: the medium shading draws only the layers' share (none near the eye).
    float share = u_medium != 0 ? layers_share(length(v_world - u_eye), v_height, thickness) : 1.0;
    if (ground <= 0.0 || share <= 0.0)
        discard;
    float detail = 1.0;
    if (u_detail > 0.0)
        detail = 1.0 - u_detail + u_detail * smoothstep(0.25, 0.75, detail_noise(v_world.xy, v_height * u_detail_layers));
    vec3 view = normalize(v_world - u_eye);
    vec3 layer_point = v_world;  // where the slab is lit (drawn at the samples: a point of one that crosses it)
    float cos_sun = dot(view, u_sun_direction);
    float a;
    vec3 radiance;
    if (u_medium != 0) {
        // In combined mode the layers draw only their share of the fog (fog_partition.glsl);
        // the sun still sees all of it.
        float density = v_alpha * tex.a * detail * ground * share;
        // The slab seen along the view, at the layer's own slant: the narrowing tilts the layers
        // near the eye away from the base (docs/layers.md), so the drawn triangle's normal.
        vec3 surface = cross(dFdx(v_world), dFdy(v_world));
        vec3 across = dot(surface, surface) > 0.0 ? normalize(surface) : normalize(v_normal);
        float cos_view = max(abs(dot(across, view)), 0.02);
        // The ray's path through the slab: the layers stand r apart vertically (the Medium's
        // columns), so on a slope the slab between them is r cos(slope) thick across. The slab
        // reaches v_slab_above of r over the layer and the rest under it (the top's lies wholly
        // under it), so a ray going down crosses that share of its path before the layer, one
        // climbing the rest. Where the ray leaves the space around the eye, which no layer
        // crosses, the path runs from the eye.
        float dist = length(v_world - u_eye);
        float path = v_spacing * v_slab * abs(across.z) / cos_view;
        float over_layer = v_slab > 0.0 ? clamp(v_slab_above / v_slab, 0.0, 1.0) : 0.5;
        float before = dot(view, across.z < 0.0 ? -across : across) < 0.0 ? over_layer : 1.0 - over_layer;
        float entry = max(dist - before * path, 0.0);
        if (leaves_the_eyes_slab(view, across, dist)) {
            // In combined mode the froxels draw the fog nearer than the layers' share begins.
            entry = u_partitioned != 0 ? min(u_partition.x, dist) : 0.0;
            path = max(path, dist + (1.0 - before) * path - entry);
        }
        // The slab ends where the ray meets the ground: the part of it beyond lies behind the
        // terrain, and where the ray enters the slab of the layer under this one before the
        // ground, the stretch pass adds that slab's fog up to it.
        float sigma = u_extinction * density;
#if defined(LAYERS_AT_SAMPLES)
        if (u_stretch_pass != 0) {
            // Each sample's ray crosses the layer at its own point (across half a pixel the layer
            // is flat): there the ground under it, along it the ground the ray meets, and the light
            // it scatters (a shore's pixel holds sunlit fog and fog in a ridge's shadow).
            float opacity = 0.0;
            vec3 plane = cross(dFdx(v_world), dFdy(v_world));
            float paths[4];
            vec3 points[4];
            for (int s = 0; s < 4; ++s) {
                paths[s] = 0.0;
                points[s] = sample_point(s, plane);
                vec3 w = points[s];
                if (w.z >= terrain_height(w.xy))
                    paths[s] = max(min(path, sample_ground_distance(s) - (entry + length(w - u_eye) - dist)), 0.0);
                sample_alpha[s] = 1.0 - exp(-sigma * paths[s]);
                opacity += sample_alpha[s];
            }
            if (!(opacity > 0.0))
                discard;
            // Each lit where it is: a shore's pixel holds sunlit fog and fog in a ridge's shadow
            // (lit once, along the sample that crosses most, the dense lake 1.4 -> 2.0 %; once where
            // the samples' paths agree within 5 %, 1.8 %).
            for (int s = 0; s < 4; ++s) {
                sample_radiance[s] = vec3(0.0);
                if (paths[s] > 0.0) {
                    vec3 w = points[s];
                    float shift = length(w - u_eye) - dist;
                    sample_radiance[s] = slab_radiance(w, normalize(w - u_eye), entry + shift, paths[s], dist + shift,
                                                       sigma, covered, column, tex.a);
                    layer_point = w;
                }
            }
            a = opacity / 4.0;
            radiance = vec3(0.0);  // each sample's own
        } else {
            a = 1.0 - exp(-sigma * path);
            radiance = slab_radiance(layer_point, view, entry, path, dist, sigma, covered, column, tex.a);
        }
#else
        if (u_stretch_pass != 0) {
            path = min(path, ground_distance() - entry);
            if (!(path > 0.0))
                discard;
        }
        a = 1.0 - exp(-sigma * path);
        radiance = slab_radiance(layer_point, view, entry, path, dist, sigma, covered, column, tex.a);
#endif
    } else {
        a = v_alpha * u_opacity * tex.a * detail;
        a = 1.0 - pow(max(1.0 - a, 0.0), v_exponent);
        a *= ground;
        // Gray, lit by the sun (forward scattering brightens it towards the sun) and the sky.
        float phase = 0.55 + 0.45 * (1.0 + cos_sun * cos_sun) * 0.5 + 0.5 * pow(max(cos_sun, 0.0), 8.0);
        float sun_up = clamp(u_sun_direction.z * 2.0 + 0.2, 0.0, 1.0);
        radiance = tex.rgb * (u_sun_radiance * sun_up * phase * 0.6 + u_ambient * 1.6);
    }
    if (a <= 1e-6)  // nothing to add; a larger threshold would bias stacks of many thin layers
        discard;
    float haze = 1.0 - exp(-length(layer_point - u_eye) * u_haze_density);
    radiance = mix(radiance, u_sky_horizon, haze);
    // The froxel fog between the eye and this layer (froxel_apply.glsl, none without it): the
    // terrain behind got the whole ray's fog F already, so over it this layer is
    // T C + a S (premultiplied), which composes to S + T (C + (1 - a) (what lies behind)).
    vec4 fog = froxel_fog(layer_point);
#if defined(LAYERS_AT_SAMPLES)
    if (u_medium == 0 || u_stretch_pass == 0) {
        sample_alpha = float[4](a, a, a, a);
        sample_radiance = vec3[4](radiance, radiance, radiance, radiance);
    }
    vec4 lit[4];
    for (int s = 0; s < 4; ++s)
        lit[s] = vec4((mix(sample_radiance[s], u_sky_horizon, haze) * fog.a + fog.rgb) * sample_alpha[s],
                      sample_alpha[s]);
    o_color = lit[0];
    o_sample1 = lit[1];
    o_sample2 = lit[2];
    o_sample3 = lit[3];
#else
    o_color = vec4((radiance * fog.a + fog.rgb) * a, a);
#endif
}
