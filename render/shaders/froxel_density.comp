#version 450 core
// Pass 1: the extinction of the Medium and of the height fog per froxel: the mean of u_samples
// samples spread evenly over the froxel's depth on the tile's central ray (the ray whose ground
// the apply knows), and where in the slice the extinction sits (its weighted mean position).
// Not jittered: the density is exact each frame, only the lighting is filtered over time. Over
// the froxels of the tiles with fog (froxel_fog_tiles.glsl); the others are cleared to 0.
layout(local_size_x = 64) in;
layout(rgba16f, binding = 0) writeonly uniform image3D o_density;
uniform int u_samples;

void main()
{
    ivec3 id = ft_froxel();
    if (id.z >= u_fx_size.z)
        return;
    vec2 range = fx_tile_range(id.xy);
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
