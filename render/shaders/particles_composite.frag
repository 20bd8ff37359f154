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
uniform sampler2DMS u_samples_color;  // the frame's samples' colour, when the frame below is their mean
uniform bool u_samples_below;         // (nothing blended into it since the resolve)
out vec4 o_color;

void main()
{
    if (u_at_samples) {
        ivec2 px = ivec2(gl_FragCoord.xy);
        vec4 c[4] = vec4[4](texelFetch(u_particles, px, 0), texelFetch(u_sample1, px, 0), texelFetch(u_sample2, px, 0),
                            texelFetch(u_sample3, px, 0));
        vec4 sum = vec4(0.0);
        vec3 through = vec3(0.0), below = vec3(0.0);
        for (int s = 0; s < 4; ++s) {
            sum += c[s];
            if (u_samples_below) {
                vec3 b = texelFetch(u_samples_color, px, s).rgb;
                through += (1.0 - c[s].a) * b;
                below += b;
            }
        }
        // Blended over the samples' mean: mean((1 - a_s) b_s) where the blend gives
        // (1 - mean a) mean b (layers_composite.frag).
        o_color = 0.25 * sum;
        if (u_samples_below)
            o_color.rgb += 0.25 * (through - (1.0 - o_color.a) * below);
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
