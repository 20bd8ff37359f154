// Library: the froxel volume's layout (render/src/froxel_pass.cpp). Froxel (i, j, k) covers the
// screen tile [i, i + 1] / size.x by [j, j + 1] / size.y and view depths between slices k and
// k + 1 of its tile's range: the slices are spread over each tile's own [first, last] depth
// (fog-aware) or over [near, far] (standard), by the distribution of froxel_slices.cpp.
uniform ivec3 u_fx_size;           // froxels across, down, slices
uniform int u_fx_distribution;     // 0 exponential, 1 log2, 2 power
uniform float u_fx_power;
uniform float u_fx_log2_scale;
uniform sampler2D u_fx_tiles;      // per tile: first and last depth (first >= last: no fog), ground at its centre
uniform float u_fx_far;            // the volume's last depth
uniform vec3 u_fx_eye;
uniform vec3 u_fx_forward;         // unit view axis
uniform vec3 u_fx_right;           // scaled: tan(fov / 2) aspect along the camera's right
uniform vec3 u_fx_up;              // scaled: tan(fov / 2) along the camera's up

float fx_slice_depth(float s, vec2 range)
{
    float a = range.x, b = range.y;
    if (u_fx_distribution == 0)
        return a * pow(b / a, s);
    if (u_fx_distribution == 1)
        return a + u_fx_log2_scale * (exp(s * log(1.0 + (b - a) / u_fx_log2_scale)) - 1.0);
    return a + (b - a) * pow(s, u_fx_power);
}

float fx_slice_coordinate(float d, vec2 range)
{
    float a = range.x, b = range.y;
    if (d <= a)
        return 0.0;
    if (d >= b)
        return 1.0;
    if (u_fx_distribution == 0)
        return log(d / a) / log(b / a);
    if (u_fx_distribution == 1)
        return log(1.0 + (d - a) / u_fx_log2_scale) / log(1.0 + (b - a) / u_fx_log2_scale);
    return pow((d - a) / (b - a), 1.0 / u_fx_power);
}

// The direction through screen point uv with unit view depth (its length converts view depth
// to distance along the ray).
vec3 fx_ray(vec2 uv)
{
    vec2 ndc = uv * 2.0 - 1.0;
    return u_fx_forward + ndc.x * u_fx_right + ndc.y * u_fx_up;
}

vec3 fx_world(vec2 uv, float depth) { return u_fx_eye + fx_ray(uv) * depth; }

vec2 fx_tile_range(ivec2 tile) { return texelFetch(u_fx_tiles, tile, 0).xy; }
float fx_tile_ground(ivec2 tile) { return texelFetch(u_fx_tiles, tile, 0).z; }
