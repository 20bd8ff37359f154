#include "layers_end.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "froxel_pass.hpp"
#include "layer_stack_uniforms.hpp"
#include "light_volume_texture.hpp"
#include "shadow_map_pass.hpp"
#include "sun_volume.hpp"

namespace kiri::render::detail {
namespace {

// Texture units: the sun volume's three (the Medium's grid, its noise, tau_sun), the layers'
// noise, the frame's depth; the froxel apply's and the shadow map's (5 .. 19, 23), the baked
// light's (20 .. 22) as in layers.frag; the base's heights.
// The frame's samples' depth (25) where each sample's fog is drawn.
constexpr int end_unit_sun = 0, end_unit_noise = 3, end_unit_depth = 4, end_unit_baked = 20, end_unit_base = 24,
              end_unit_samples = 25;
// Steps of the sun's march where a point lies outside the sun volume (as the layers' columns).
constexpr int end_sun_march_steps = 32;
// Texels of the base's height map along its longer side.
constexpr int end_base_texels = 512;
constexpr float end_outside = -1e30f;

}  // namespace

void LayersEnd::set_base(const geometry::LayerBase& base)
{
    const glm::dvec2 lo(base.min), hi(base.max);
    const glm::dvec2 extent = glm::max(hi - lo, glm::dvec2(1e-6));
    const double cell = std::max(extent.x, extent.y) / end_base_texels;
    const int nx = std::clamp(int(std::ceil(extent.x / cell)), 1, end_base_texels),
              ny = std::clamp(int(std::ceil(extent.y / cell)), 1, end_base_texels);
    std::vector<float> z(std::size_t(nx) * ny, end_outside);
    // Each texel's centre in the triangle under it, interpolated as the GPU draws the base.
    for (std::size_t t = 0; t + 2 < base.triangles.size(); t += 3) {
        const glm::dvec3 &a = base.position[base.triangles[t]], &b = base.position[base.triangles[t + 1]],
                         &c = base.position[base.triangles[t + 2]];
        const double area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
        if (!(std::abs(area) > 0.0))
            continue;
        const auto texel = [&](double v, double o, double e, int n) { return (v - o) / e * n - 0.5; };
        const int i0 = std::max(0, int(std::ceil(texel(std::min({a.x, b.x, c.x}), lo.x, extent.x, nx))));
        const int i1 = std::min(nx - 1, int(std::floor(texel(std::max({a.x, b.x, c.x}), lo.x, extent.x, nx))));
        const int j0 = std::max(0, int(std::ceil(texel(std::min({a.y, b.y, c.y}), lo.y, extent.y, ny))));
        const int j1 = std::min(ny - 1, int(std::floor(texel(std::max({a.y, b.y, c.y}), lo.y, extent.y, ny))));
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) {
                const double x = lo.x + (i + 0.5) * extent.x / nx, y = lo.y + (j + 0.5) * extent.y / ny;
                const double wb = ((x - a.x) * (c.y - a.y) - (c.x - a.x) * (y - a.y)) / area;
                const double wc = ((b.x - a.x) * (y - a.y) - (x - a.x) * (b.y - a.y)) / area;
                const double wa = 1.0 - wb - wc;
                if (wa < -1e-9 || wb < -1e-9 || wc < -1e-9)
                    continue;
                z[std::size_t(j) * nx + i] = float(wa * a.z + wb * b.z + wc * c.z);
            }
    }
    heights_ = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(heights_.get(), 1, GL_R32F, nx, ny);
    glTextureSubImage2D(heights_.get(), 0, 0, 0, nx, ny, GL_RED, GL_FLOAT, z.data());
    glTextureParameteri(heights_.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(heights_.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(heights_.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(heights_.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    rect_ = glm::vec4(float(lo.x), float(lo.y), float(1.0 / extent.x), float(1.0 / extent.y));
}

void LayersEnd::draw(const Inputs& in)
{
    if (!heights_ || !in.sun)
        return;
    const geometry::LayerOptions& o = in.options;
    const bool baked = o.optics.multiple_scattering == geometry::MultipleScattering::baked && in.light_volume &&
        in.light_volume->ready();
    std::unique_ptr<ShaderProgram>& slot = programs_[in.fog ? 1 : 0][baked ? 1 : 0][in.at_samples != nullptr ? 1 : 0];
    if (!slot)
        slot = std::make_unique<ShaderProgram>(
            // The vertex stage first: the libraries are the fragment stage's (layers_light.glsl
            // reads the fragment's samples).
            std::vector<std::string_view>{
                "fullscreen.vert", "medium_shell.glsl", "light_volume.glsl", "fog_partition.glsl", "froxel_common.glsl",
                "fog_lighting.glsl", "terrain_shadow.glsl", "height_fog.glsl", "froxel_medium.glsl", "sun_march.glsl",
                "sun_volume.glsl", in.fog ? "froxel_apply.glsl" : "froxel_fog_none.glsl", "layers_light.glsl",
                "layers_end.frag"},
            std::string(light_volume_preamble(baked)) +
                (in.at_samples != nullptr ? "#define LAYERS_AT_SAMPLES\n" : ""));
    const ShaderProgram& p = *slot;
    if (in.fog)
        in.fog->bind_apply(p);
    bind_terrain_shadow(p, in.shadow);
    in.sun->bind(p, end_unit_sun, end_sun_march_steps);
    if (in.light_volume)
        in.light_volume->bind(p, end_unit_baked, baked);
    else
        LightVolumeTexture{}.bind(p, end_unit_baked, false);
    in.sun->bind_grid(p, end_unit_baked + 1);  // after the baked light's binding of the same grid
    set_layer_stack_uniforms(p, o, glm::dvec2(0.0), in.frame.eye, 0, 0);
    set_layers_light_uniforms(p, o, in.frame, in.noise_shift);
    set_partition_uniforms(p, in.frame);
    set_eye_in_stack_uniforms(p, in.eye);
    p.set("u_inverse_view_projection", in.frame.inverse_view_projection);
    p.set("u_noise", end_unit_noise);
    p.set("u_frame_depth", end_unit_depth);
    p.set("u_base_heights", end_unit_base);
    p.set("u_base_rect", rect_);
    p.use();
    glBindTextureUnit(end_unit_noise, in.noise);
    glBindTextureUnit(end_unit_depth, in.resolved_depth);
    if (in.at_samples) {
        p.set("u_frame_samples", end_unit_samples);
        glProgramUniform2fv(p.id(), p.location("u_sample_offsets"), 8, in.at_samples->offsets);
        glBindTextureUnit(end_unit_samples, in.at_samples->depth);
    }
    glBindTextureUnit(end_unit_base, heights_.get());
    if (!empty_vao_)
        empty_vao_ = make_vertex_array();
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glBindVertexArray(empty_vao_.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_BLEND);
}

}  // namespace kiri::render::detail
