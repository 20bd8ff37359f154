#version 450 core
// Puts the particles (premultiplied linear radiance E and coverage A, accumulated back to front
// in their own float target) over the frame's linear radiance: E + (1 - A) what is there. The
// near billboards' coarser target is upsampled bilinearly. A still drawn at its samples
// (particles.frag's PARTICLES_AT_SAMPLES) has each sample's blend in a target of its own: each
// sample's colour is seen through its own.
in vec2 v_ndc;
uniform sampler2D u_particles;
uniform vec2 u_inv_size;  // 1 / the frame's size; (0, 0): the target is the frame's size
uniform bool u_at_samples;
uniform sampler2D u_sample1;  // samples 1..3's blends (u_particles: sample 0's)
uniform sampler2D u_sample2;
uniform sampler2D u_sample3;
out vec4 o_color;

void main()
{
    if (u_at_samples) {
        ivec2 px = ivec2(gl_FragCoord.xy);
        vec4 c[8] = vec4[8](texelFetch(u_particles, px, 0), texelFetch(u_sample1, px, 0), texelFetch(u_sample2, px, 0),
                            texelFetch(u_sample3, px, 0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0));
        o_color = blends_over_samples(c, 4, px);
        if (o_color.a <= 1e-6 && all(lessThanEqual(abs(o_color.rgb), vec3(1e-6))))
            discard;
        return;
    }
    vec4 c = u_inv_size.x > 0.0 ? textureLod(u_particles, gl_FragCoord.xy * u_inv_size, 0.0)
                                : texelFetch(u_particles, ivec2(gl_FragCoord.xy), 0);
    if (c.a <= 1e-6)
        discard;
    o_color = c;
}
