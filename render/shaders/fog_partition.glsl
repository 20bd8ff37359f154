// geometry/fog_partition.hpp on the GPU: the share of the Medium each renderer draws in
// combined mode. u_partition = (near_start, near_end, particle_share, particle_band);
// u_partitioned = 0 draws the whole Medium (every share 1).
uniform vec4 u_partition;
uniform int u_partitioned;

float smoother_step(float a, float b, float x)
{
    if (!(b > a))
        return x >= a ? 1.0 : 0.0;
    float t = clamp((x - a) / (b - a), 0.0, 1.0);
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

float particle_share(float h)
{
    return u_partition.z > 0.0 ? u_partition.z * smoother_step(1.0 - u_partition.w, 1.0, h) : 0.0;
}

// The layers' share at view distance d and shell height h.
float layers_share(float d, float h)
{
    if (u_partitioned == 0)
        return 1.0;
    return (1.0 - particle_share(h)) * smoother_step(u_partition.x, u_partition.y, d);
}

// The froxels' share.
float froxels_share(float d, float h)
{
    if (u_partitioned == 0)
        return 1.0;
    return (1.0 - particle_share(h)) * (1.0 - smoother_step(u_partition.x, u_partition.y, d));
}
