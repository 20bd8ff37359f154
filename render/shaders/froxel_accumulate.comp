#version 450 core
// Pass 2b for a still picture: the lighting samples of one view averaged. The view does not move,
// so each froxel is its own history: no reprojection, and no clamp to the current sample's
// neighbourhood (a clamp rejects what a moving view changed; here it would only pull the mean
// towards the last sample). With u_weight = k / (k + 1) after k samples the result is their mean.
// Froxels not lit (a < 0) say nothing about J, as in froxel_temporal.comp; both parts of a lit one
// (J in the terrain's shadow, the sun's share: froxel_lighting.comp) are averaged.
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(rgba16f, binding = 0) writeonly uniform image3D o_resolved;
uniform sampler3D u_current;
uniform sampler3D u_history;
uniform int u_history_valid;
uniform float u_weight;

void main()
{
    ivec3 id = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(id, u_fx_size)))
        return;
    vec4 current = texelFetch(u_current, id, 0);
    vec4 j = current;
    if (u_history_valid != 0) {
        vec4 history = texelFetch(u_history, id, 0);
        if (current.a >= 0.0 && history.a >= 0.0)
            j = mix(current, history, u_weight);
    }
    imageStore(o_resolved, id, j);
}
