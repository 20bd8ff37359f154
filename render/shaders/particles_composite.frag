#version 450 core
// Puts the particles (premultiplied linear radiance E and coverage A, accumulated back to front
// in their own float target) over the frame's linear radiance: E + (1 - A) what is there.
in vec2 v_ndc;
uniform sampler2D u_particles;
out vec4 o_color;

void main()
{
    vec4 c = texelFetch(u_particles, ivec2(gl_FragCoord.xy), 0);
    if (c.a <= 1e-6)
        discard;
    o_color = c;
}
