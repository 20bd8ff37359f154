#version 450 core
// Puts the particles (premultiplied linear radiance E and coverage A, accumulated back to front
// in their own float target) over the frame's linear radiance: E + (1 - A) what is there. The
// near billboards' coarser target is upsampled bilinearly.
in vec2 v_ndc;
uniform sampler2D u_particles;
uniform vec2 u_inv_size;  // 1 / the frame's size; (0, 0): the target is the frame's size
out vec4 o_color;

void main()
{
    vec4 c = u_inv_size.x > 0.0 ? textureLod(u_particles, gl_FragCoord.xy * u_inv_size, 0.0)
                                : texelFetch(u_particles, ivec2(gl_FragCoord.xy), 0);
    if (c.a <= 1e-6)
        discard;
    o_color = c;
}
