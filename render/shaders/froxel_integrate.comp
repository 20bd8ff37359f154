#version 450 core
// Pass 3: front to back through each tile's slices, energy-conserving ([Hillaire15]): a slice
// of extinction sigma, source S = sigma J and length l adds T (S - S exp(-sigma l)) / sigma
// = T J (1 - exp(-sigma l)) and multiplies T by exp(-sigma l). Slice k stores (in-scattered
// radiance, T) at its far end.
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba16f, binding = 0) writeonly uniform image3D o_integrated;
uniform sampler3D u_light;    // (J, lit)
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
    float stretch = length(fx_ray((vec2(t) + 0.5) / vec2(u_fx_size.xy)));
    vec3 radiance = vec3(0.0);
    float transmittance = 1.0;
    float d0 = range.x;
    for (int k = 0; k < u_fx_size.z; ++k) {
        float d1 = fx_slice_depth(float(k + 1) / float(u_fx_size.z), range);
        vec4 v = texelFetch(u_light, ivec3(t, k), 0);
        vec2 m = texelFetch(u_density, ivec3(t, k), 0).xy;
        float sigma = m.x + m.y, l = (d1 - d0) * stretch;
        float through = exp(-sigma * l);
        vec3 added = v.a > 0.0 ? v.rgb * (sigma * l > 1e-5 ? 1.0 - through : sigma * l) : vec3(0.0);
        radiance += transmittance * added;
        transmittance *= through;
        imageStore(o_integrated, ivec3(t, k), vec4(radiance, transmittance));
        d0 = d1;
    }
}
