#version 450 core
// Puts the particles (premultiplied linear radiance E and coverage A, accumulated back to front
// in a float target) over the tonemapped frame: A tonemap(E / A) over what is there.
in vec2 v_ndc;
uniform sampler2D u_particles;
uniform float u_exposure;
out vec4 o_color;

vec3 tonemap(vec3 radiance) { return pow(vec3(1.0) - exp(-radiance * u_exposure), vec3(1.0 / 2.2)); }

void main()
{
    vec4 c = texelFetch(u_particles, ivec2(gl_FragCoord.xy), 0);
    if (c.a <= 1e-6)
        discard;
    o_color = vec4(tonemap(c.rgb / c.a) * c.a, c.a);
}
