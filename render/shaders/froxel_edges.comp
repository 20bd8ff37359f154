#version 450 core
// The froxels' apply at a pixel whose samples see different fog: the resolve averaged their
// colours and took one depth, and one march along the pixel's centre fogs them all alike.
// - Two surfaces (a ridge against the fogged valley behind it): the resolve took the depth of one
//   side (depth_resolve.frag: the side most samples lie on, the nearer on a tie), so one march at
//   that depth would fog the other side's colour as if it lay there too, and a ridge's edge
//   against a valley's fog would alias. The split is the resolve's own (depth_samples.glsl).
// - Fogged unevenly (a thread of fog in a valley narrower than the pixel, seen from afar; the
//   fog's top meeting a slope; the fog's side wall): the samples' estimates of the fog just
//   before their surfaces (fog_before) split at their largest gap where it exceeds u_fog_split in
//   transmittance, or else in the share of the view their fog's sunlit skin takes (a dense fog's
//   top in and out of the terrain's shadow); on two surfaces too, where each side by the fog lies
//   on one of them.
// Such a pixel's samples each march their own ray to their own surface (froxel_pixels.comp, an
// invocation a sample) and the pixel takes their mean. Not one ray a side: seen from afar at a
// grazing angle a quarter of a pixel is tens of metres of height, and where the fog's top cuts
// the ground within the pixel the fog before a side's mean surface point is not the mean of its
// samples' (the lake from afar: a side's mean ray let 0.59 of the light through where its three
// samples let 0.08, 0.13 and 0.22; 2.8 % off the reference with one ray a side, 0.7 % with a ray
// a sample).
// Per pixel split: o_split 1 (0: one fog, the centre's stands for the pixel), o_split_ray the
// bounds of its samples' rays' stretch of the shell (froxel_pixels.comp's u_split_ray); the pixel
// listed (FrameMarches) for its samples' marches, and counted in fm_sampled where split by its fog.
layout(local_size_x = 8, local_size_y = 8) in;
uniform sampler2DMS u_ms_depth;
uniform float u_fog_split;  // 0: split two surfaces alone
layout(r8, binding = 0) writeonly uniform image2D o_split;
layout(rg32f, binding = 1) writeonly uniform image2D o_split_ray;

// The largest gap between values v[0..n) in order, and the value halfway across it.
float largest_gap(float v[ds_max], int n, out float at)
{
    float gap = 0.0;
    at = 0.0;
    for (int s = 0; s < ds_max && s < n; ++s) {
        float next = 2.0;
        for (int r = 0; r < ds_max && r < n; ++r)
            if (v[r] > v[s])
                next = min(next, v[r]);
        if (next <= 1.0 && next - v[s] > gap) {
            gap = next - v[s];
            at = 0.5 * (v[s] + next);
        }
    }
    return gap;
}

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= u_size.x || px.y >= u_size.y)
        return;
    float lo, hi, centre;
    float marches = 0.0;  // 1: the samples march
    // The pixels' shell around it, for the probes and the split's bounds: once, here (llvmpipe
    // runs its loop in each call, known or not).
    fog_before_for_pixel(px);
    fog_before_pixels_shell();
    if (u_samples > 1) {
        bool two = ds_read(u_ms_depth, px, u_near_plane, u_far_plane, lo, hi, centre);
        uint other = 0u;    // the other side's samples, a bit each
        float under = 0.0;  // the longest stretch of a sample's ray under the fog's top (fog_before)
        if (two) {
            float split = 0.5 * (lo + hi);
            bool resolved_near = texelFetch(u_depth, px, 0).r <= split;
            for (int s = 0; s < ds_max && s < u_samples; ++s)
                other |= (ds[s] <= split) != resolved_near ? 1u << s : 0u;
        }
        if (u_fog_split > 0.0 && (u_fx_shell != 0 || u_hf.x > 0.0) && hi < 1.0) {
            float t[ds_max], lit[ds_max];
            vec4 skin[ds_max];
            float haze[ds_max];
            float fogged = 0.0, sigma;
            uint probed = 0u;  // the samples whose fog before them is probed, a bit each
            for (int s = 0; s < ds_max && s < u_samples; ++s) {
                vec2 uv = frame_uv(px) + u_offsets[s] / vec2(u_size);
                bool probe;
                under = max(under, fog_before_column(uv, view_depth(ds[s], u_near_plane, u_far_plane), t[s], skin[s],
                                                     sigma, haze[s], probe));
                probed |= probe ? 1u << s : 0u;
            }
            // Only those samples probed, one a pass (llvmpipe runs the probes once a pass of a
            // loop whatever its lanes need: each sample's call of fog_before ran them).
            while (probed != 0u) {
                int s = findLSB(probed);
                probed &= probed - 1u;
                vec2 uv = frame_uv(px) + u_offsets[s] / vec2(u_size);
                under = max(under, fog_before_probed(fx_ray(uv), view_depth(ds[s], u_near_plane, u_far_plane), haze[s],
                                                     t[s], skin[s], sigma));
            }
            for (int s = 0; s < ds_max && s < u_samples; ++s)
                fogged = max(fogged, skin[s].w);
            float at, at_lit;
            float gap = largest_gap(t, u_samples, at);
            // Or by the fog's light where its transmittance is alike: a dense fog's sunlit skin
            // meeting the terrain's shadow within the pixel, every sample's fog opaque (the dense
            // lake: 18 of its 67 pixels over 10 % off the reference, the centre's light for all).
            // (The share lit is at most the fog's share: the terrain's shadow looked up only where
            // that can pass the threshold.)
            bool by_light = false;
            if (!(gap > u_fog_split) && fogged > u_fog_split) {
                for (int s = 0; s < ds_max && s < u_samples; ++s)
                    lit[s] = skin[s].w > 0.0 ? skin[s].w * terrain_visibility(skin[s].xyz, u_ts_bias) : 0.0;
                by_light = largest_gap(lit, u_samples, at_lit) > u_fog_split;
            }
            if (by_light) {
                for (int s = 0; s < ds_max && s < u_samples; ++s)
                    t[s] = lit[s] > at_lit ? 0.0 : 1.0;  // the sides by their light
                gap = 1.0;
                at = 0.5;
            }
            // Split by the fog, also where the samples see two surfaces if each side by the fog
            // lies on one of them (no jump within it): a fogged valley floor and the slope above
            // it may lie off one plane, and a split by the depth then fogs the slope's samples
            // that stand with the floor's as the floor.
            uint by_fog = 0u;
            float near_clear = 1.0, far_clear = 0.0, near_fogged = 1.0, far_fogged = 0.0;
            for (int s = 0; s < ds_max && s < u_samples; ++s)
                if (t[s] > at) {
                    by_fog |= 1u << s;
                    near_clear = min(near_clear, ds[s]);
                    far_clear = max(far_clear, ds[s]);
                } else {
                    near_fogged = min(near_fogged, ds[s]);
                    far_fogged = max(far_fogged, ds[s]);
                }
            const float jump = 1.25;
            bool one_each = view_depth(far_clear, u_near_plane, u_far_plane) <=
                    jump * view_depth(near_clear, u_near_plane, u_far_plane) &&
                view_depth(far_fogged, u_near_plane, u_far_plane) <=
                    jump * view_depth(near_fogged, u_near_plane, u_far_plane);
            if (gap > u_fog_split && (!two || one_each)) {
                other = by_fog;
                two = false;
            } else {
                under = 0.0;
            }
        }
        if (other != 0u) {
            marches = 1.0;
            // The rays' stretch of the shell: within those of the pixels around it (rasterised at
            // their centres); under a thread of fog narrower than a pixel none may have one, so
            // from the fog's top before the nearest surface on (3e38: each ray's end).
            vec2 shell = u_fx_shell != 0 ? fog_before_pixels_shell() : vec2(3e38, 0.0);
            if (!two) {
                float nearest = view_depth(lo, u_near_plane, u_far_plane);
                shell = vec2(min(shell.x, nearest - 1.5 * under), 3e38);
                atomicAdd(fm_sampled, 1u);
            }
            // One invocation a sample (froxel_pixels.comp): a group of 64 takes 64 / u_samples pixels.
            fm_list(uint(px.x) | (uint(px.y) << 16), uint(64 / u_samples));
            imageStore(o_split_ray, px, vec4(shell, 0.0, 0.0));  // read only where the pixel is listed
        }
    }
    imageStore(o_split, px, vec4(marches));
}
