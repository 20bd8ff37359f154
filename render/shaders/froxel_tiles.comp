#version 450 core
// Per tile: the depths its slices span. Standard: [near, far]. Fog-aware: from the nearest
// shell entry to the farthest shell exit in front of the ground over the tile's pixels (and a
// pixel around), padded; where fog may be anywhere (eye inside the shell): from near to the
// farthest ground; with a height fog, its pixels' ranges too: from where each ray comes down to
// the height fog's top (8 scale heights over its base; the eye if below it) to its ground, so
// that the slices stay where the fog is seen (from 20 km, [near, ground] spread them over
// kilometres, the blanket's light in one or two: 5 % off where the blanket lay over a haze).
// Empty tiles get first >= last. The third channel keeps the ground's depth at the tile's
// centre (3e38: sky) for the apply.
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) writeonly uniform image2D o_tiles;
uniform sampler2D u_shell_depths;  // per pixel: -(shell's nearest depth) (-3e38: none), its farthest (0)
uniform sampler2D u_ground;  // the frame's depth buffer
uniform ivec2 u_raster;      // the frame's size
uniform ivec2 u_tiles;
uniform float u_near_plane;  // of the raster's projection
uniform float u_far_plane;
uniform float u_near;        // of the volume
uniform float u_far;
uniform int u_mode;          // 0 standard, 1 shell, 2 everywhere in front of the ground, 3 shell and haze
uniform float u_pad;         // relative padding of fog-aware ranges
uniform mat4 u_inverse_view_projection;
uniform vec3 u_eye;
uniform vec3 u_forward;      // unit view axis
uniform float u_haze_top;    // mode 3: the height fog's top

// Mode 3: the view depth at which pixel r's ray comes down to the height fog's top (near: the eye
// is under it; 3e38: the ray never does).
float haze_entry(ivec2 r)
{
    if (u_eye.z <= u_haze_top)
        return u_near;
    vec2 ndc = (vec2(r) + 0.5) / vec2(u_raster) * 2.0 - 1.0;
    vec4 far_point = u_inverse_view_projection * vec4(ndc, 1.0, 1.0);
    vec3 ray = far_point.xyz / far_point.w - u_eye;
    float along = dot(ray, u_forward);  // view depth per unit of ray
    if (!(ray.z < 0.0) || !(along > 0.0))
        return 3e38;
    return (u_eye.z - u_haze_top) / -ray.z * along;
}


void main()
{
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (t.x >= u_tiles.x || t.y >= u_tiles.y)
        return;
    ivec2 centre = clamp(ivec2((vec2(t) + 0.5) * vec2(u_raster) / vec2(u_tiles)), ivec2(0), u_raster - 1);
    float centre_ground = view_depth_or_sky(texelFetch(u_ground, centre, 0).r, u_near_plane, u_far_plane);
    if (u_mode == 0) {
        imageStore(o_tiles, t, vec4(u_near, u_far, centre_ground, 0.0));
        return;
    }
    ivec2 r0 = t * u_raster / u_tiles;
    ivec2 r1 = max((t + 1) * u_raster / u_tiles, r0 + 1);
    float first = 3e38, last = 0.0;             // the shell's
    float haze_first = 3e38, haze_last = 0.0;   // the height fog's
    for (int y = r0.y - 1; y <= r1.y; ++y)
        for (int x = r0.x - 1; x <= r1.x; ++x) {
            ivec2 r = clamp(ivec2(x, y), ivec2(0), u_raster - 1);
            float ground = view_depth_or_sky(texelFetch(u_ground, r, 0).r, u_near_plane, u_far_plane);
            if (u_mode == 2) {
                first = u_near;
                last = max(last, ground);
                continue;
            }
            vec2 shell = texelFetch(u_shell_depths, r, 0).rg;
            float a = -shell.x;
            float b = min(shell.y, ground);
            if (a < b) {
                first = min(first, a);
                last = max(last, b);
            }
            if (u_mode == 3) {
                float entry = haze_entry(r);
                if (entry < ground) {
                    haze_first = min(haze_first, entry);
                    haze_last = max(haze_last, ground);
                }
            }
        }
    // Combined mode: no froxel fog beyond near_end from the eye (depth <= distance), so the
    // slices stay where the froxels draw (the height fog's they draw at every distance).
    if (u_partitioned != 0 && (u_mode == 1 || u_mode == 3))
        last = min(last, u_partition.y);
    if (u_mode == 3 && haze_last > haze_first) {
        first = min(first, haze_first);
        last = max(last, haze_last);
    }
    first = max(first * (1.0 - u_pad), u_near);
    last = min(last * (1.0 + u_pad), u_far);
    imageStore(o_tiles, t, last > first ? vec4(first, last, centre_ground, 0.0) : vec4(0.0, 0.0, centre_ground, 0.0));
}
