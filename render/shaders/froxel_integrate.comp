#version 450 core
// Pass 3: front to back through each tile's slices, energy-conserving ([Hillaire15]): a slice
// of extinction sigma, source S = sigma J and length l adds T (S - S exp(-sigma l)) / sigma
// = T J (1 - exp(-sigma l)) and multiplies T by exp(-sigma l). Slice k stores (in-scattered
// radiance, T) at its far end. J of the Medium from the lighting pass, in two parts (J in the
// terrain's shadow, the sun's share), the terrain's visibility of the sun between them taken along
// the tile's central ray through the slice (segment_visibility); the height fog's lit along
// the tile's central ray where it is seen (froxel_light.glsl, HazeRuns), short of the ground that
// ray meets: its light changes over tens of metres, its froxels are hundreds of metres deep from
// afar.
// FROXEL_HEIGHT_FOG 0: the variant for scenes without one (froxel_march.glsl says why).
#ifndef FROXEL_HEIGHT_FOG
#define FROXEL_HEIGHT_FOG 1
#endif
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba16f, binding = 0) writeonly uniform image3D o_integrated;
uniform sampler3D u_light;    // (J in the terrain's shadow, the sun's share); a < 0: not lit
uniform sampler3D u_density;  // (sigma_t of the Medium, of the height fog, ...)

void main()
{
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (t.x >= u_fx_size.x || t.y >= u_fx_size.y)
        return;
    vec2 range = fx_tile_range(t);
    if (!(range.y > range.x)) {
        for (int k = 0; k < u_fx_size.z; ++k)
            imageStore(o_integrated, ivec3(t, k), vec4(0.0, 0.0, 0.0, 1.0));
        return;
    }
    // Metres along the tile's central ray per metre of view depth.
    vec2 uv = (vec2(t) + 0.5) / vec2(u_fx_size.xy);
    float stretch = length(fx_ray(uv));
    float ground = 0.998 * fx_tile_ground(t);  // the height fog's light and the visibility short of it
#if FROXEL_HEIGHT_FOG
    // Twice through the slices: first where the height fog's light is needed (its runs,
    // froxel_light.glsl), then, with each run lit once, the sums.
    HazeRuns runs = haze_runs_along_ray();
    {
        float transmittance = 1.0;
        float d0 = range.x;
        for (int k = 0; k < u_fx_size.z; ++k) {
            float d1 = fx_slice_depth(float(k + 1) / float(u_fx_size.z), range);
            vec2 m = texelFetch(u_density, ivec3(t, k), 0).xy;
            float sigma = m.x + m.y, l = (d1 - d0) * stretch;
            float through = exp(-sigma * l);
            float opacity = sigma * l > 1e-5 ? transmittance * (1.0 - through) / sigma : transmittance * l;
            if (m.y > 0.0)
                haze_run_step(runs, opacity * m.y, fx_world(uv, min(d0, ground)), fx_world(uv, min(d1, ground)),
                              m.y * l);
            transmittance *= through;
            d0 = d1;
        }
    }
    // Each run's light (without one, the heaviest step's at its middle: a segment of no length),
    // one call of it in a loop the compiler keeps (haze_runs_finish says why); at constant
    // indices (haze_run_a says why).
    vec3 light0 = vec3(0.0), light1 = vec3(0.0);
    bool lone = runs.count == 0 && runs.before > 1e-5;
    for (int i = 0; i < (lone ? 1 : runs.count); ++i) {
        vec3 j = height_fog_segment_light(lone ? runs.at : haze_run_a(runs, i), lone ? runs.at : haze_run_b(runs, i),
                                          u_fx_eye, lone ? 0.0 : haze_run_tau(runs, i));
        if (i == 0)
            light0 = j;
        else
            light1 = j;
    }
    HazeRuns replay = haze_runs_along_ray();
#endif
    vec3 radiance = vec3(0.0);
    float transmittance = 1.0;
    float d0 = range.x;
    float visible_d0 = -1.0;  // the terrain's visibility of the sun at d0 where the slice before took it
    for (int k = 0; k < u_fx_size.z; ++k) {
        float d1 = fx_slice_depth(float(k + 1) / float(u_fx_size.z), range);
        vec4 v = texelFetch(u_light, ivec3(t, k), 0);
        vec2 m = texelFetch(u_density, ivec3(t, k), 0).xy;
        float sigma = m.x + m.y, l = (d1 - d0) * stretch;
        float through = exp(-sigma * l);
        float opacity = sigma * l > 1e-5 ? transmittance * (1.0 - through) / sigma : transmittance * l;
        float visible_d1 = -1.0;
        if (v.a >= 0.0 && m.x > 0.0) {
            // The visibility along the tile's central ray through the slice (segment_visibility,
            // froxel_light.glsl), short of the ground.
            vec3 a = fx_world(uv, min(d0, ground)), b = fx_world(uv, min(d1, ground));
            float visible = 0.0;
            if (v.a > 0.0)
                visible = segment_visibility(a, b, visible_d0, visible_d1);
            radiance += opacity * m.x * medium_light_from_parts(v, visible);
        }
        visible_d0 = visible_d1;
#if FROXEL_HEIGHT_FOG
        if (m.y > 0.0) {
            haze_run_step(replay, opacity * m.y, fx_world(uv, min(d0, ground)), fx_world(uv, min(d1, ground)), m.y * l);
            radiance += opacity * m.y * (replay.count <= 1 ? light0 : light1);
        }
#endif
        transmittance *= through;
        imageStore(o_integrated, ivec3(t, k), vec4(radiance, transmittance));
        d0 = d1;
    }
}
