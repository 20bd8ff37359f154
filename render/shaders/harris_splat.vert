#version 450 core
// Harris's light pass: one particle's footprint as a quad in the light buffer (orthographic
// along the light). u_particle: centre in pixels (x, y) and radius in pixels (z).
uniform vec3 u_particle;
uniform vec2 u_buffer_size;
void main()
{
    vec2 corner = vec2((gl_VertexID & 1) == 0 ? -1.0 : 1.0, (gl_VertexID & 2) == 0 ? -1.0 : 1.0);
    vec2 pixel = u_particle.xy + corner * (u_particle.z + 1.0);
    gl_Position = vec4(pixel / u_buffer_size * 2.0 - 1.0, 0.0, 1.0);
}
