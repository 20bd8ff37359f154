#version 450 core
// Linear radiance -> display: exponential exposure, then the sRGB transfer curve (gamma 2.2).
// The one place of the frame where radiance becomes a colour.
uniform sampler2D u_hdr;
uniform float u_exposure;
out vec4 o_color;

void main()
{
    vec3 radiance = max(texelFetch(u_hdr, ivec2(gl_FragCoord.xy), 0).rgb, vec3(0.0));
    o_color = vec4(pow(vec3(1.0) - exp(-radiance * u_exposure), vec3(1.0 / 2.2)), 1.0);
}
