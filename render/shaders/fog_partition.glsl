// geometry/fog_partition.hpp on the GPU: the share of the Medium each renderer draws in
// combined mode. u_partition = (near_start, near_end, particle_share, particle_band);
// u_partition_depth = the fog's thickness (metres) where the particles' share starts and where it
// is whole (particle_depth_share; y <= 0: every thickness); u_partitioned = 0 draws the whole
// Medium (every share 1).
uniform vec4 u_partition;
uniform vec2 u_partition_depth;
uniform int u_partitioned;

float smoother_step(float a, float b, float x)
{
    if (!(b > a))
        return x >= a ? 1.0 : 0.0;
    float t = clamp((x - a) / (b - a), 0.0, 1.0);
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

// At shell height h, in fog `thickness` metres thick (top - floor of its column).
float particle_share(float h, float thickness)
{
    if (!(u_partition.z > 0.0))
        return 0.0;
    float depth = u_partition_depth.y > 0.0 ? smoother_step(u_partition_depth.x, u_partition_depth.y, thickness) : 1.0;
    return u_partition.z * smoother_step(1.0 - u_partition.w, 1.0, h) * depth;
}

// The layers' share at view distance d, shell height h and fog thickness t.
float layers_share(float d, float h, float t)
{
    if (u_partitioned == 0)
        return 1.0;
    return (1.0 - particle_share(h, t)) * smoother_step(u_partition.x, u_partition.y, d);
}

// The froxels' share.
float froxels_share(float d, float h, float t)
{
    if (u_partitioned == 0)
        return 1.0;
    return (1.0 - particle_share(h, t)) * (1.0 - smoother_step(u_partition.x, u_partition.y, d));
}
