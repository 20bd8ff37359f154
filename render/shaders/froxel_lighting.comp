#version 450 core
// Pass 2: the Medium's lighting per froxel (froxel_light.glsl, docs/froxel.md) as J = S / sigma_t,
// the in-scattered radiance per unit of its extinction. J is smooth where the density is not: it
// is what the temporal filter blends and what the integration weighs by the Medium's density.
// Stored in two parts (medium_light_parts_at): (J in the terrain's shadow, the sun's share), the
// integration taking the terrain's visibility of the sun along each tile's ray through a slice;
// (0, -1) where skipped: froxels without the Medium (standard slicing), or every froxel of a tile
// without fog (fog-aware). The height fog is lit where it is
// integrated and marched, at its own points (froxel_integrate.comp, froxel_march.glsl): a haze
// tens of metres deep changes its light within a froxel, and one J for both media let the
// haze's light stand for the Medium's where a froxel held both.
layout(local_size_x = 64) in;  // over the froxels of the tiles with fog (froxel_fog_tiles.glsl)
layout(rgba16f, binding = 0) writeonly uniform image3D o_light;
uniform sampler3D u_density;
uniform vec3 u_jitter;
uniform float u_sun_jitter;
uniform int u_whole_tiles;    // light every froxel of a tile with fog, not only those with fog

void main()
{
    ivec3 id = ft_froxel();
    if (id.z >= u_fx_size.z)
        return;
    vec4 density = texelFetch(u_density, id, 0);
    vec2 range = fx_tile_range(id.xy);
    if (u_md_on == 0 || !(u_whole_tiles != 0 ? range.y > range.x : density.x > 0.0)) {
        imageStore(o_light, id, vec4(0.0, 0.0, 0.0, -1.0));
        return;
    }
    vec2 uv = (vec2(id.xy) + u_jitter.xy) / vec2(u_fx_size.xy);
    float d0 = fx_slice_depth(float(id.z) / float(u_fx_size.z), range);
    float d1 = fx_slice_depth(float(id.z + 1) / float(u_fx_size.z), range);
    // Lit where the tile's central ray still is above the ground: froxels beyond it (pixels of
    // the tile see farther) take the light of the ray's last point before the ground, not that
    // of a point inside the hill.
    vec3 p = fx_world(uv, min(mix(d0, d1, density.z), 0.998 * fx_tile_ground(id.xy)));
    imageStore(o_light, id, medium_light_parts_at(p, u_fx_eye, u_sun_jitter));
}
