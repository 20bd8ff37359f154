#version 450 core
// The fog a ray crosses just before it meets the terrain, in the slab of a layer it never
// crosses (the medium shading; drawn before the stack, the farthest piece of each ray).
//
// A layer stands for the slab of fog around it, and a ray takes a slab's fog where it crosses the
// layer (layers.frag), from the slab's one side to the other. A ray that meets the terrain inside
// a slab before it reaches that slab's layer takes nothing of it: the stretch from where it
// entered the slab (the boundary half-way between two layers, or the eye, for a ray that never
// left the space between the two layers either side of it) to the terrain. Seen steeply that is
// less than half a spacing; at a grazing angle (a valley's wall seen from inside its fog, the
// eye on a layer looking level) it is hundreds of metres of fog, and the terrain showed through.
// Here each pixel of terrain adds that stretch, a slab of the fog at its height, lit as a layer
// is at the centroid of its emission along it.
in vec2 v_ndc;
uniform sampler2D u_base_heights;       // the layers' base under (x, y) (R32F, -1e30 outside it)
uniform vec4 u_base_rect;               // x0, y0, 1 / extent x, 1 / extent y
uniform float u_thickness;              // T0
uniform float u_max_count;
uniform float u_divisor;                // 200 of (2.6)
uniform int u_narrowing;
uniform float u_top_loss;
uniform float u_extinction;
uniform vec3 u_sky_horizon;
uniform float u_haze_density;
out vec4 o_color;
#if defined(LAYERS_AT_SAMPLES)
// Each sample's own blend of the stack (layers.frag): each sample's fog before its own ground.
layout(location = 1) out vec4 o_sample1;
layout(location = 2) out vec4 o_sample2;
layout(location = 3) out vec4 o_sample3;
#endif

// The fog before `ground` (premultiplied; 0: none).
vec4 end_fog(vec3 ground)
{
    vec3 ray = ground - u_eye;
    float reach = length(ray);
    if (!(reach > 0.0))
        return vec4(0.0);
    vec3 view = ray / reach;
    // The stack over the terrain point, as layers.vert spaces it there.
    float base = texture(u_base_heights, (ground.xy - u_base_rect.xy) * u_base_rect.zw).r;
    if (!(base > -1e29) || !(ground.z >= base))
        return vec4(0.0);
    float r0 = u_thickness / u_count;
    float r = r0;
    float to_base = length(u_eye - vec3(ground.xy, base));
    if (u_narrowing != 0)
        r = r0 * clamp(to_base / (u_divisor * r0), 0.0, 1.0);
    r = max(r, u_thickness / u_max_count);
    float n = u_thickness / r;
    float j = floor((ground.z - base) / r);  // the terrain point lies between layers j and j + 1
    if (j >= floor(n))
        return vec4(0.0);  // over the stack's whole layers
    // The stretch of the ray in the slab it ends in, before the terrain.
    float stretch;
    if (u_eye_inside != 0 && reach <= u_first_reach && j == eye_region(view)) {
        stretch = reach;  // between the eye's two layers all the way: no layer crossed
    } else {
        float boundary = base + (j + 0.5) * r;  // between slab j and slab j + 1
        float below = ground.z - boundary;      // > 0: the terrain point in slab j + 1
        // The ray ends in a slab it entered through the boundary: climbing into slab j + 1, or
        // descending into slab j. Otherwise it ends in the slab of the layer it crossed last,
        // which took that slab up to the terrain (layers.frag).
        if (!(abs(view.z) > 0.0) || (view.z > 0.0) != (below > 0.0))
            return vec4(0.0);
        stretch = min(reach, abs(below) / abs(view.z));
    }
    // The fog there: the Medium's coverage, the layers' profile at the height, the detail.
    vec3 middle = ground - view * (0.5 * stretch);
    float height = clamp((middle.z - base) / u_thickness, 0.0, 1.0);
    vec4 column = shell_covers(middle.xy) ? shell_column(middle.xy) : vec4(0.0);
    float detail = 1.0;
    if (u_detail > 0.0)
        detail = 1.0 - u_detail + u_detail * smoothstep(0.25, 0.75, detail_noise(middle.xy, height * u_detail_layers));
    float share = layers_share(distance(middle, u_eye), height, column.z - column.x);
    float density = column.w * (1.0 - u_top_loss * height) * detail * share;
    float sigma = u_extinction * density;
    float a = 1.0 - exp(-sigma * stretch);
    if (!(a > 1e-6))
        return vec4(0.0);
    // Lit where its light comes from: the centroid of its emission from the stretch's near end.
    vec3 lit = ground - view * stretch + view * emission_centroid(stretch, sigma * stretch);
    vec3 s = u_sun_direction;
    float visible = s.z > 0.0 ? path_visibility(ground - view * stretch, view, stretch, sigma * stretch,
                                                 visibility_points(stretch, r))
                              : 0.0;
    vec3 radiance = fog_source(dot(view, s), sun_optical_depth(lit, s, 0.5), visible);
    if (u_lv_on != 0)
        radiance += u_albedo * u_sun_radiance * lv_in_scattered_at(lit, -view, u_anisotropy, true);
    radiance = mix(radiance, u_sky_horizon, 1.0 - exp(-distance(lit, u_eye) * u_haze_density));
    vec4 fog = froxel_fog(ground - view * stretch);
    return vec4((radiance * fog.a + fog.rgb) * a, a);
}

void main()
{
    vec3 ground;
#if defined(LAYERS_AT_SAMPLES)
    vec4 c[4];
    for (int s = 0; s < 4; ++s)
        c[s] = sample_ground(s, ground) ? end_fog(ground) : vec4(0.0);
    if (!(max(max(c[0].a, c[1].a), max(c[2].a, c[3].a)) > 0.0))
        discard;
    o_color = c[0];
    o_sample1 = c[1];
    o_sample2 = c[2];
    o_sample3 = c[3];
#else
    if (!frame_ground(v_ndc * 0.5 + 0.5, ground))
        discard;  // the sky: the ray leaves the fog through a layer or its side
    o_color = end_fog(ground);
    if (!(o_color.a > 0.0))
        discard;
#endif
}
