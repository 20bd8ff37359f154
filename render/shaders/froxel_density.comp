#version 450 core
// Pass 1: the extinction of the Medium and of the height fog per froxel: the mean of u_samples
// samples spread evenly over the froxel's depth on the tile's central ray (the ray whose ground
// the apply knows), and where in the slice the extinction sits (its weighted mean position).
// Not jittered: the density is exact each frame, only the lighting is filtered over time.
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(rgba16f, binding = 0) writeonly uniform image3D o_density;
uniform int u_samples;

void main()
{
    ivec3 id = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(id, u_fx_size)))
        return;
    vec2 range = fx_tile_range(id.xy);
    if (!(range.y > range.x)) {
        imageStore(o_density, id, vec4(0.0));
        return;
    }
    vec2 uv = (vec2(id.xy) + 0.5) / vec2(u_fx_size.xy);
    float d0 = fx_slice_depth(float(id.z) / float(u_fx_size.z), range);
    float d1 = fx_slice_depth(float(id.z + 1) / float(u_fx_size.z), range);
    vec3 ray = fx_ray(uv);
    float medium = 0.0, haze = 0.0, where = 0.0;
    for (int k = 0; k < u_samples; ++k) {
        float f = (float(k) + 0.5) / float(u_samples);
        vec3 p = u_fx_eye + ray * mix(d0, d1, f);
        float m = froxel_sigma(p), h = height_fog_sigma(p);
        medium += m;
        haze += h;
        where += f * (m + h);
    }
    float total = medium + haze;
    imageStore(o_density, id, vec4(medium, haze, total > 0.0 ? where / total : 0.5, 0.0) / vec4(u_samples, u_samples, 1.0, 1.0));
}
