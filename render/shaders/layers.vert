#version 450 core
// The layer stack ([Thesis] 2.2.3) drawn as instances of the base tessellation: instance k is
// layer i (those over the eye top first, then those under it bottom first). Mirrors
// geometry::layer_column / layer_vertex
// (geometry/src/layers/layer_stack.cpp): per-vertex spacing narrowed near the eye (2.8),
// real-valued count keeping the thickness (2.9) with the partial top layer faded in, alpha
// (2.7), enlargement about the centre (2.10).
layout(location = 0) in vec3 a_position;  // base surface, world metres
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;        // into the border-mask atlas

uniform mat4 u_view_projection;
uniform vec3 u_eye;
uniform vec2 u_centre;
uniform float u_thickness;   // T0
uniform float u_count;       // l0
uniform float u_max_count;
uniform float u_divisor;     // 200 of (2.6)
uniform float u_rate;        // 1/1000 of (2.10)
uniform int u_narrowing;
uniform int u_enlargement;
uniform int u_top;           // layers above the base drawn this frame
uniform int u_first_instance; // this draw's first instance of the stack (a stack in two draws)
uniform int u_under;         // layers under the eye (geometry::layers_under_eye): drawn last, bottom first
uniform float u_time;
uniform float u_half_life;   // 0: no dissipation
uniform float u_top_loss;    // 0.9 of (2.7); 1 - top_density of the medium

out vec3 v_world;
out vec2 v_uv;
out float v_alpha;
out float v_exponent;
out float v_spacing;        // r (m): the spacing of the layers here
out float v_slab;           // the share of r that this layer's slab of fog spans (layer_slab_share)
out float v_slab_above;     // of it, the share of r above the layer (layer_slab_share_above)
out float v_height;         // h = i / n in [0, 1]: where in the fog's thickness
out vec3 v_normal;
// The baked multiple scattering towards the eye at the vertex (light_volume.glsl; 0 unless the
// model is `baked`): its cells span hundreds of metres, so a triangle interpolates it well, at a
// fraction of a lookup per fragment.
out float v_baked;
uniform float u_anisotropy;
flat out int v_layer;

// geometry::layer_slab_share: the stack as the trapezoid rule over the fog's thickness, with nodes
// at the layers 0..m (m = floor(n)) and the top at n, the partial layer m + 1 standing in for it
// (its fade-in, n - m, is in v_alpha).
float layer_slab_share(float n, int i)
{
    float m = floor(n), part = n - m, k = float(i);
    return (k >= 1.0 && k <= m ? 0.5 : 0.0) + (k <= m - 1.0 ? 0.5 : 0.0) + (k == m ? 0.5 * part : 0.0) +
           (k == m + 1.0 ? 0.5 : 0.0);
}

// geometry::layer_slab_share_above: the trapezoids' halves above the layer (none for the top's).
float layer_slab_share_above(float n, int i)
{
    float m = floor(n), part = n - m, k = float(i);
    return (k <= m - 1.0 ? 0.5 : 0.0) + (k == m ? 0.5 * part : 0.0);
}

void main()
{
    int instance = gl_InstanceID + u_first_instance;
    // The layers over the eye top first, then those under it bottom first: far to near along a ray.
    int over = u_top + 1 - u_under;
    int i = instance < over ? u_top - instance : instance - over;
    vec3 p = a_position;
    v_uv = a_uv;
    v_layer = i;
    if (u_count <= 0.0) {  // the base alone
        v_world = p;
        v_alpha = i == 0 ? 1.0 : 0.0;
        v_exponent = 1.0;
        v_spacing = u_thickness;
        v_slab = 1.0;
        v_slab_above = 0.5;
        v_height = 0.0;
        v_normal = a_normal;
        v_baked = u_lv_on != 0 ? lv_in_scattered_at(p, normalize(u_eye - p), u_anisotropy, true) : 0.0;
        gl_Position = u_view_projection * vec4(p, 1.0);
        return;
    }
    float r0 = u_thickness / u_count;
    float r = r0;
    vec3 d = u_eye - p;
    float L = length(d);
    if (u_narrowing != 0) {
        float L0 = u_divisor * r0;
        r = r0 * (1.0 - clamp((L0 - L) / L0, 0.0, 1.0));
    }
    r = max(r, u_thickness / u_max_count);
    float n = u_thickness / r;
    float sin_theta = (u_enlargement != 0 && L > 0.0) ? min(abs(dot(a_normal, d)) / L, 1.0) : 0.0;
    float fi = float(i);
    float fade_in = clamp(n + 1.0 - fi, 0.0, 1.0);
    v_height = min(fi, n) / n;
    v_alpha = fade_in * (1.0 - u_top_loss * v_height);
    if (u_half_life > 0.0 && u_time > 0.0)
        v_alpha *= exp2(-u_time / u_half_life * (1.0 + min(fi / n, 1.0)));
    v_exponent = r / r0;
    v_spacing = r;
    v_slab = layer_slab_share(n, i);
    v_slab_above = layer_slab_share_above(n, i);
    v_normal = a_normal;
    float scale = 1.0 + fi * u_rate * sin_theta;
    vec2 xy = u_centre + scale * (p.xy - u_centre);
    v_world = vec3(xy, p.z + fi * r);
    v_baked = u_lv_on != 0 ? lv_in_scattered_at(v_world, normalize(u_eye - v_world), u_anisotropy, true) : 0.0;
    gl_Position = u_view_projection * vec4(v_world, 1.0);
}
