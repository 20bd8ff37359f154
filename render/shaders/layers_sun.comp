#version 450 core
// tau_sun (sun_volume.glsl) along the column above each vertex of the layers' base, at u_levels
// heights evenly from the base up to u_height above it: the layers' vertices read it there
// (layers.vert), a lookup per layer vertex without a texture fetch, rebuilt with the sun volume.
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Vertices { float vertices[]; };  // LayersPass's Vertex: 8 floats
layout(std430, binding = 1) writeonly buffer Columns { float columns[]; };
uniform vec3 u_sun_direction;
uniform int u_vertices;
uniform int u_levels;
uniform float u_height;

void main()
{
    int v = int(gl_GlobalInvocationID.x);
    if (v >= u_vertices)
        return;
    vec3 base = vec3(vertices[8 * v], vertices[8 * v + 1], vertices[8 * v + 2]);
    for (int k = 0; k < u_levels; ++k) {
        vec3 p = base + vec3(0.0, 0.0, u_height * float(k) / float(u_levels - 1));
        columns[v * u_levels + k] = sun_optical_depth(p, u_sun_direction, 0.5);
    }
}
