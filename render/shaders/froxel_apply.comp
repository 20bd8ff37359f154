#version 450 core
// Pass 4 over the frame: the fog each pixel of the resolved linear-radiance frame (RGBA16F,
// before the tone map) gets at its depth, radiance T + in-scattered radiance, from u_fog (the
// fog-aware apply's froxel_upsample.comp and froxel_pixels.comp: (in-scattered radiance, T)).
layout(local_size_x = 32, local_size_y = 8) in;
layout(rgba16f, binding = 0) uniform image2D io_color;
uniform sampler2D u_fog;
uniform ivec2 u_size;

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= u_size.x || px.y >= u_size.y)
        return;
    vec4 fog = texelFetch(u_fog, px, 0);
    if (!(fog.a >= 1.0 && all(equal(fog.rgb, vec3(0.0))))) {
        vec4 c = imageLoad(io_color, px);
        imageStore(io_color, px, vec4(c.rgb * fog.a + fog.rgb, c.a));
    }
}
