#version 450 core
// The footprint's light gain G(rho) at this pixel's centre; blended as dst * src, so the buffer
// holds the product of the gains of every particle drawn so far (Harris's I_k / I0).
uniform vec3 u_particle;  // centre (pixels), radius (pixels)
uniform vec3 u_optics;    // radius (m), tau, albedo
uniform float u_pixel_m;
out vec4 o_gain;
void main()
{
    float rho = length(gl_FragCoord.xy - u_particle.xy) * u_pixel_m;
    o_gain = vec4(exp(footprint_log_gain(rho, u_optics.x, u_optics.y, u_optics.z, u_forward)));
}
