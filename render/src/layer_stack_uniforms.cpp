#include "layer_stack_uniforms.hpp"

namespace kiri::render::detail {

void set_layer_stack_uniforms(const ShaderProgram& p, const geometry::LayerOptions& o, const glm::dvec2& centre,
                              const glm::vec3& eye, int top, int under)
{
    p.set("u_eye", eye);
    p.set("u_centre", glm::vec2(centre));
    p.set("u_thickness", float(o.thickness));
    p.set("u_count", float(o.count));
    p.set("u_max_count", float(o.max_count));
    p.set("u_divisor", float(o.spacing_divisor));
    p.set("u_rate", float(o.enlargement_rate));
    p.set("u_narrowing", int(o.narrowing));
    p.set("u_enlargement", int(geometry::layers_enlarge(o)));
    p.set("u_top", top);
    p.set("u_under", under);
    p.set("u_time", float(o.optics.time));
    p.set("u_half_life", float(o.optics.dissipation_half_life));
    // (2.7)'s 0.9, or the medium's profile 1 - (1 - top_density) h (layer_vertex).
    const bool medium = o.shading == geometry::LayerShading::medium;
    p.set("u_top_loss", float(medium ? 1.0 - o.optics.top_density : 0.9));
}

}  // namespace kiri::render::detail
