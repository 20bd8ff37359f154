#version 450 core
// Fog-aware tiles over the Medium's shell: a tile's range ends where the fog along its central
// ray has become opaque (optical depth 9, transmittance 1e-4), the distance from the range's
// first depth to there doubled (the tile's other pixels enter later). In a dense fog the
// slices and each pixel's steps then lie in the metres the eye sees, not hundreds of metres
// deep where nothing is seen: J near the fog's sunlit top changes within metres.
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) uniform image2D io_tiles;
uniform int u_steps;

void main()
{
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(t, u_fx_size.xy)))
        return;
    vec4 tile = imageLoad(io_tiles, t);
    if (!(tile.y > tile.x))
        return;
    vec3 ray = fx_ray((vec2(t) + 0.5) / vec2(u_fx_size.xy));
    float stretch = length(ray), tau = 0.0, d0 = tile.x;
    for (int k = 1; k <= u_steps; ++k) {
        float d1 = tile.x * pow(tile.y / tile.x, float(k) / float(u_steps));
        float dt = (d1 - d0) * stretch;
        float sigma = froxel_sigma(u_fx_eye + ray * (0.5 * (d0 + d1)));
        if (tau + sigma * dt >= 9.0) {  // opaque within this step: where exactly, then cut
            float d = d0 + (9.0 - tau) / max(sigma * stretch, 1e-20);
            tile.y = min(tile.y, tile.x + 2.0 * (d - tile.x));
            imageStore(io_tiles, t, tile);
            return;
        }
        tau += sigma * dt;
        d0 = d1;
    }
}
