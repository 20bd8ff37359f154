#include "layer_stack_uniforms.hpp"

#include <algorithm>

#include "kiri/geometry/medium/fog_lighting.hpp"
#include "render_origin.hpp"
#include "sun_volume.hpp"

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

void set_eye_in_stack_uniforms(const ShaderProgram& p, const EyeInStack& eye)
{
    p.set("u_eye_inside", int(eye.inside && eye.spacing > 0.0));
    p.set("u_eye_base", float(eye.base_z));
    p.set("u_eye_spacing", float(std::max(eye.spacing, 1e-6)));
    p.set("u_first_reach", float(eye.reach));
}

void set_layers_light_uniforms(const ShaderProgram& p, const geometry::LayerOptions& o, const FrameContext& frame,
                               const glm::dvec2& noise_shift)
{
    p.set("u_detail", float(o.optics.detail));
    p.set("u_detail_scale", float(o.optics.detail_scale));
    p.set("u_detail_layers", float(o.optics.detail_layers));
    p.set("u_drift", glm::vec2(noise_drift(o.optics.wind, o.optics.time, noise_shift, 8.0 * o.optics.detail_scale)));
    p.set("u_sun_direction", sun_march_direction(frame.sun_direction));
    p.set("u_sun_radiance", frame.sun_radiance);
    p.set("u_ambient", frame.ambient);
    p.set("u_sky_horizon", frame.sky_horizon);
    p.set("u_haze_density", frame.haze_density);
    p.set("u_extinction", float(o.optics.extinction));
    p.set("u_albedo", float(o.optics.albedo));
    p.set("u_octaves", geometry::shader_octaves(o.optics));
    p.set("u_anisotropy", float(std::clamp(o.optics.anisotropy, -0.999, 0.999)));
}

}  // namespace kiri::render::detail
