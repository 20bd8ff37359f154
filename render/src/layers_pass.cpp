#include "layers_pass.hpp"

#include "depth_pass.hpp"
#include "render_origin.hpp"

#include "kiri/geometry/layers/layer_lod.hpp"
#include "light_volume_texture.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "froxel_pass.hpp"
#include "layer_stack_uniforms.hpp"
#include "kiri/geometry/terrain/heightfield.hpp"
#include "noise_texture.hpp"
#include "sun_volume.hpp"

namespace kiri::render::detail {
namespace {

struct LayersPassVertex {
    float position[3];
    float normal[3];
    float uv[2];
};

// The baked light's Medium grid and moments in layers.frag, apart from the atlas (0), the
// heights (1), the noise (2), the shadow map and the froxel apply's units (5 .. 19).
constexpr int layers_unit_baked_moments =
    20;  // and 21, 22: the Medium's grid, the cells' floors (LightVolumeTexture::bind)
// The frame's resolved depth in layers.frag, after the baked light's and the shadow map's (23).
constexpr int layers_unit_ground_depth = 24;
constexpr int layers_unit_sun = 25;      // 25, 26, 27: sun_volume.glsl's in layers.frag
constexpr int layers_unit_samples = 28;  // the frame's samples' depth (LAYERS_AT_SAMPLES)
// Steps of the sun's march where a fragment lies outside the sun volume's grid.
constexpr int sun_march_steps = 32;

// Whether a layer of the stack of layers 0..top over `base` (layer i at most i r0 over it, r0 =
// thickness / count, enlarged about its centre by at most 1 + top rate) comes within `reach` of
// the eye: the base's bounds grown so.
bool stack_within(const geometry::LayerBase& base, const geometry::LayerOptions& o, int top, const glm::dvec3& eye,
                  double reach)
{
    const double rise = double(top) * o.thickness / double(std::max(o.count, 1));
    const double grow = o.enlargement ? double(top) * o.enlargement_rate : 0.0;
    const glm::dvec2 c = base.centre;
    const glm::dvec2 lo = glm::min(glm::dvec2(base.min), c + (1.0 + grow) * (glm::dvec2(base.min) - c));
    const glm::dvec2 hi = glm::max(glm::dvec2(base.max), c + (1.0 + grow) * (glm::dvec2(base.max) - c));
    const glm::dvec3 nearest = glm::clamp(eye, glm::dvec3(lo, base.min.z), glm::dvec3(hi, base.max.z + rise));
    return glm::distance(nearest, eye) < reach;
}

void set_sampling(GLuint texture, GLint filter)
{
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, filter);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, filter);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

}  // namespace

LayersPass::LayersPass()
    : composite_(
          {"view_depth.glsl", "depth_samples.glsl", "fullscreen.vert", "sample_blends.glsl", "layers_composite.frag"}),
      depth_max_({"view_depth.glsl", "fullscreen.vert", "layers_depth_max.frag"}), empty_vao_(make_vertex_array()),
      noise_(make_noise_texture())
{}

bool LayersPass::set_base(const geometry::LayerBase& base)
{
    base_ = &base;
    if (uploaded_base_ == base.position.data() && uploaded_base_size_ == base.position.size() && index_count_ > 0)
        return false;
    std::vector<LayersPassVertex> vertices(base.position.size());
    for (std::size_t i = 0; i < vertices.size(); ++i) {
        const glm::dvec3& p = base.position[i];
        const glm::dvec3& n = base.normal[i];
        vertices[i] = {{float(p.x), float(p.y), float(p.z)},
                       {float(n.x), float(n.y), float(n.z)},
                       {float(base.atlas_uv[i].x), float(base.atlas_uv[i].y)}};
    }
    vao_ = make_vertex_array();
    vertices_ = make_buffer();
    indices_ = make_buffer();
    glNamedBufferStorage(vertices_.get(), GLsizeiptr(vertices.size() * sizeof(LayersPassVertex)), vertices.data(), 0);
    glNamedBufferStorage(indices_.get(), GLsizeiptr(base.triangles.size() * sizeof(std::uint32_t)),
                         base.triangles.data(), 0);
    glVertexArrayVertexBuffer(vao_.get(), 0, vertices_.get(), 0, sizeof(LayersPassVertex));
    glVertexArrayElementBuffer(vao_.get(), indices_.get());
    const GLuint sizes[3] = {3, 3, 2};
    const GLuint offsets[3] = {0, 3 * sizeof(float), 6 * sizeof(float)};
    for (GLuint a = 0; a < 3; ++a) {
        glEnableVertexArrayAttrib(vao_.get(), a);
        glVertexArrayAttribFormat(vao_.get(), a, GLint(sizes[a]), GL_FLOAT, GL_FALSE, offsets[a]);
        glVertexArrayAttribBinding(vao_.get(), a, 0);
    }
    index_count_ = GLsizei(base.triangles.size());
    near_reach_ = -1.0;  // a new base: its triangles near the eye are still to be found
    lod_levels_.clear();
    lod_active_ = false;

    const geometry::LayerTexture& t = base.texture;
    atlas_ = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(atlas_.get(), 1, GL_RGBA8, t.width, t.height);
    glTextureSubImage2D(atlas_.get(), 0, 0, 0, t.width, t.height, GL_RGBA, GL_UNSIGNED_BYTE, t.rgba.data());
    set_sampling(atlas_.get(), GL_LINEAR);
    end_.set_base(base);
    uploaded_base_ = base.position.data();
    uploaded_base_size_ = base.position.size();
    return true;
}

void LayersPass::set_ground(const geometry::Heightfield& hf, double exaggeration)
{
    ground_ = &hf;
    ground_exaggeration_ = exaggeration;
}

bool LayersPass::upload_ground()
{
    if (!ground_ || ground_->nx < 2 || ground_->ny < 2)
        return false;
    const geometry::Heightfield& hf = *ground_;
    const double exaggeration = ground_exaggeration_;
    if (uploaded_heights_ == hf.z.data() && uploaded_exaggeration_ == exaggeration && heights_)
        return false;
    std::vector<float> z(hf.z.size());
    for (std::size_t i = 0; i < z.size(); ++i)
        z[i] = float(hf.z[i] * exaggeration);
    heights_ = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(heights_.get(), 1, GL_R32F, hf.nx, hf.ny);
    glTextureSubImage2D(heights_.get(), 0, 0, 0, hf.nx, hf.ny, GL_RED, GL_FLOAT, z.data());
    set_sampling(heights_.get(), GL_LINEAR);
    const double ex = std::max(hf.x_max() - hf.x0, 1e-9), ey = std::max(hf.y_max() - hf.y0, 1e-9);
    height_rect_ = {float(hf.x0), float(hf.y0), float(1.0 / ex), float(1.0 / ey)};
    height_texels_ = {float(hf.nx), float(hf.ny)};
    uploaded_heights_ = hf.z.data();
    uploaded_exaggeration_ = exaggeration;
    return true;
}

void LayersPass::stack_bounds(glm::dvec3& lo, glm::dvec3& hi) const
{
    // The base raised by the thickness (plus the partial top layer) and grown by the largest
    // enlargement about the centre.
    const double grow = 1.0 + options_.max_count * options_.enlargement_rate;
    lo = base_->min;
    hi = base_->max;
    for (int k = 0; k < 2; ++k) {
        lo[k] = base_->centre[k] + grow * (lo[k] - base_->centre[k]);
        hi[k] = base_->centre[k] + grow * (hi[k] - base_->centre[k]);
    }
    hi.z += options_.thickness * (1.0 + 1.0 / std::max(options_.count, 1));
}

void LayersPass::extend_bounds(glm::dvec3& lo, glm::dvec3& hi) const
{
    if (!has_layers() || !base_)
        return;
    glm::dvec3 a, b;
    stack_bounds(a, b);
    lo = glm::min(lo, a);
    hi = glm::max(hi, b);
}

bool LayersPass::visible(const FrameContext& frame) const
{
    if (!has_layers() || !base_)
        return false;
    glm::dvec3 lo, hi;
    stack_bounds(lo, hi);
    if (frame.partitioned && options_.shading == geometry::LayerShading::medium) {
        // Combined mode: the layers draw only the fog beyond near_start (fog_partition.glsl), and
        // none of the stack may lie that far from the eye (an eye in a small fog, or a scene that
        // gives the froxels every distance).
        const glm::dvec3 eye(frame.eye);
        const glm::dvec3 farthest = glm::max(glm::abs(lo - eye), glm::abs(hi - eye));
        if (glm::length(farthest) <= double(frame.partition.x))
            return false;
    }
    return box_in_view(frame, lo, hi);
}

bool LayersPass::ready(const FrameContext& frame, bool& uploaded)
{
    last_layers_ = 0;
    last_triangles_ = 0;
    uploaded = false;
    if (!visible(frame))
        return false;
    uploaded = upload_ground();
    return bool(heights_);
}

bool LayersPass::draw(const FrameContext& frame)
{
    bool uploaded = false;
    if (ready(frame, uploaded))
        draw_stack(frame, frame.height);
    return uploaded;
}

void LayersPass::ensure_low(int width, int height, bool at_samples)
{
    if (width == low_width_ && height == low_height_ && low_fbo_ && at_samples == low_at_samples_)
        return;
    low_color_ = make_texture(GL_TEXTURE_2D);
    low_depth_ = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(low_color_.get(), 1, GL_RGBA32F, width, height);  // hundreds of blends of small alphas
    glTextureStorage2D(low_depth_.get(), 1, GL_DEPTH_COMPONENT32F, width, height);
    // Nearest: the composite does its own depth-aware bilinear weights.
    set_sampling(low_color_.get(), GL_NEAREST);
    set_sampling(low_depth_.get(), GL_NEAREST);
    low_fbo_ = make_framebuffer();
    glNamedFramebufferTexture(low_fbo_.get(), GL_COLOR_ATTACHMENT0, low_color_.get(), 0);
    glNamedFramebufferTexture(low_fbo_.get(), GL_DEPTH_ATTACHMENT, low_depth_.get(), 0);
    attach_sample_blends(low_fbo_.get(), low_samples_, width, height, GL_RGBA32F, at_samples);
    low_width_ = width;
    low_height_ = height;
    low_at_samples_ = at_samples;
}

// The setting is chosen for the frames users look at (1280 x 720 and up), where a reduced texel
// is a small angle of the view. On a small frame the same scale blurs the fog's edges and its
// threads over a wide angle (a 160 x 90 frame at 0.5: a texel a 45th of the view's height) and
// saves a few thousand fragments: there the target keeps min_reduced_texels.
double LayersPass::reduced_scale(double scale, int width, int height)
{
    const double pixels = double(std::max(width, 1)) * double(std::max(height, 1));
    return std::clamp(std::max(scale, std::sqrt(min_reduced_texels / pixels)), 0.0, 1.0);
}

bool LayersPass::draw_reduced(const FrameContext& frame, double setting, unsigned resolved_fbo, unsigned resolved_depth,
                              const FrameSamples& samples)
{
    bool uploaded = false;
    if (!ready(frame, uploaded))
        return uploaded;
    const double scale = reduced_scale(setting, frame.width, frame.height);
    const int w = std::max(1, int(std::ceil(frame.width * scale))),
              h = std::max(1, int(std::ceil(frame.height * scale)));
    // A still at the frame's resolution: each slab along the rays of its pixel's samples, each
    // sample's blend of them in a target of its own (layers.frag's LAYERS_AT_SAMPLES). It costs
    // the layers pass about 4x (every slab lit at each sample): a moving view's frames (the
    // preview's, at its floor a frame of 160 x 90) draw at the centre.
    const bool at_samples = w == frame.width && h == frame.height && samples.depth != 0 && samples.offsets != nullptr &&
        samples.count == 4 && options_.shading == geometry::LayerShading::medium && sun_ && sun_->medium() &&
        frame.still;
    ensure_low(w, h, at_samples);
    // The terrain's depth per low-resolution texel: the farthest it covers, the nearest across a
    // silhouette (layers_depth_max.frag).
    glBindFramebuffer(GL_FRAMEBUFFER, low_fbo_.get());
    glViewport(0, 0, w, h);
    depth_max_.set("u_depth", 0);
    depth_max_.set("u_scale", glm::vec2(float(double(w) / frame.width), float(double(h) / frame.height)));
    const glm::vec2 planes = depth_planes(frame);
    depth_max_.set("u_near", planes.x);
    depth_max_.set("u_far", planes.y);
    depth_max_.set("u_samples_depth", 1);
    depth_max_.set("u_samples", at_samples ? samples.count : 1);
    depth_max_.use();
    glBindTextureUnit(0, resolved_depth);
    glBindTextureUnit(1, at_samples ? samples.depth : 0);
    draw_fullscreen_depth(empty_vao_.get());
    const float clear[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (int b = 0; b < (at_samples ? 4 : 1); ++b)
        glClearNamedFramebufferfv(low_fbo_.get(), GL_COLOR, b, clear);
    draw_stack(frame, h, resolved_depth, at_samples ? &samples : nullptr);

    composite_.set("u_layers", 0);
    composite_.set("u_low_depth", 1);
    composite_.set("u_depth", 2);
    composite_.set("u_samples_depth", 3);
    composite_.set("u_samples_color", 4);
    composite_.set("u_samples_below", samples.color != 0 ? 1 : 0);
    composite_.set("u_at_samples", int(at_samples));
    composite_.set("u_layer_samples[0]", 5);
    composite_.set("u_layer_samples[1]", 6);
    composite_.set("u_layer_samples[2]", 7);
    composite_.set("u_samples", samples.depth && samples.offsets ? samples.count : 1);
    if (samples.offsets)
        glProgramUniform2fv(composite_.id(), composite_.location("u_offsets"), 8, samples.offsets);
    composite_.set("u_low_size", glm::vec2(float(w), float(h)));
    composite_.set("u_near", planes.x);
    composite_.set("u_far", planes.y);
    composite_.use();
    glBindTextureUnit(0, low_color_.get());
    glBindTextureUnit(1, low_depth_.get());
    glBindTextureUnit(2, resolved_depth);
    glBindTextureUnit(3, samples.depth);
    glBindTextureUnit(4, samples.color);
    for (int s = 0; s < 3; ++s)
        glBindTextureUnit(GLuint(5 + s), at_samples ? low_samples_[s].get() : 0);
    glBindFramebuffer(GL_FRAMEBUFFER, resolved_fbo);
    glViewport(0, 0, frame.width, frame.height);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glBindVertexArray(empty_vao_.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    return uploaded;
}

void LayersPass::update_lod(const FrameContext& frame, int target_height)
{
    const bool wanted = options_.lod > 0.0 && !base_->grid.empty();
    if (!wanted) {
        if (lod_active_)
            near_reach_ = -1.0;  // the near triangles were the level of detail's
        lod_active_ = false;
        lod_levels_.clear();
        return;
    }
    const double pixels_per_radian = 0.5 * double(target_height) * frame.projection[1][1];
    std::vector<int> levels =
        geometry::layer_lod_levels(*base_, glm::dvec3(frame.eye), pixels_per_radian, options_.lod, options_.thickness);
    if (lod_active_ && levels == lod_levels_)
        return;
    lod_triangles_ = geometry::layer_lod_triangles(base_->grid, levels);
    lod_levels_ = std::move(levels);
    lod_indices_ = make_buffer();
    glNamedBufferStorage(lod_indices_.get(),
                         GLsizeiptr(std::max<std::size_t>(lod_triangles_.size(), 1) * sizeof(std::uint32_t)),
                         lod_triangles_.empty() ? nullptr : lod_triangles_.data(), 0);
    lod_count_ = GLsizei(lod_triangles_.size());
    lod_active_ = true;
    near_reach_ = -1.0;  // the near triangles come from the new list
}

const ShaderProgram& LayersPass::stack_program(bool froxel_fog, int baked, bool at_samples)
{
    std::unique_ptr<ShaderProgram>& p = programs_[froxel_fog ? 1 : 0][std::clamp(baked, 0, 2)][at_samples ? 1 : 0];
    if (!p)
        p = std::make_unique<ShaderProgram>(
            std::vector<std::string_view>{"medium_shell.glsl", "light_volume.glsl", "layers.vert", "fog_partition.glsl",
                                          "froxel_common.glsl", "fog_lighting.glsl", "terrain_shadow.glsl",
                                          "height_fog.glsl", "froxel_medium.glsl", "sun_march.glsl", "sun_volume.glsl",
                                          froxel_fog ? "froxel_apply.glsl" : "froxel_fog_none.glsl",
                                          "layers_light.glsl", "layers.frag"},
            std::string(light_volume_preamble(baked > 0)) +
                (baked == 2 ? "" : "#define LAYERS_BAKED_PER_FRAGMENT 0\n") +
                (at_samples ? "#define LAYERS_AT_SAMPLES\n" : ""));
    return *p;
}

void LayersPass::draw_stack(const FrameContext& frame, int target_height, unsigned resolved_depth,
                            const FrameSamples* at_samples)
{
    update_lod(frame, target_height);
    const auto& o = options_;
    // The baked multiple scattering: the moments, and the Medium's columns they follow.
    const bool medium = o.shading == geometry::LayerShading::medium;
    const bool baked = medium && o.optics.multiple_scattering == geometry::MultipleScattering::baked && light_volume_ &&
        light_volume_->ready();
    const glm::dvec3 eye(frame.eye);
    const int top = geometry::layers_for_eye(*base_, options_, eye);
    // L0 = divisor r0 ([Thesis] 2.8), within which the spacing narrows, and the flat radius within
    // which it has reached its floor T0 / max_count, L0 count / max_count.
    const double reach = o.spacing_divisor * o.thickness / std::max(o.count, 1);
    const double flat = reach * double(std::max(o.count, 1)) / double(std::max(o.max_count, 1));
    // With froxel fog, the variant that reads it at each layer's depth (froxel_apply.glsl); with
    // the baked light per fragment only where a layer comes within L0 of the eye (llvmpipe runs a
    // branch's code in every fragment: the lookup cost the default view's layers 40 % more).
    // With the eye within L0 of the stack, the triangles within L0 of it are drawn with the
    // per-fragment variant and the rest with the per-vertex one (every fragment of a program pays
    // for its code: the ridge camera's layers pass 1.84x `fitted`'s with the one program).
    const bool split = baked && stack_within(*base_, o, top, eye, 1.01 * reach);
    // The samples' rays where the slabs end at the ground (the stretch pass's fog before it).
    const bool stretch = resolved_depth != 0 && o.shading == geometry::LayerShading::medium && sun_ && sun_->medium();
    const bool sampled = stretch && at_samples != nullptr;
    const ShaderProgram& p = stack_program(fog_ != nullptr, baked ? 1 : 0, sampled);
    const ShaderProgram& near_program = stack_program(fog_ != nullptr, split ? 2 : (baked ? 1 : 0), sampled);
    last_layers_ = top;
    last_triangles_ = int(drawn_triangles().size() / 3);
    const geometry::LayerStackUnder at_eye = geometry::layer_stack_under(*base_, options_, eye);
    const int under = std::isfinite(eye.z) ? geometry::layers_under_eye(at_eye, options_, eye, top) : 0;
    // Where the eye's rays start: the space between the layers either side of it, which they
    // leave within about the flat radius (without the narrowing, about L0).
    const EyeInStack in_stack{under >= 1 && under <= top, at_eye.base_z, at_eye.spacing,
                              o.narrowing ? 4.0 * flat : 2.0 * reach};
    // The fog before the terrain in the slabs the rays end in: the farthest piece of each ray,
    // drawn first, by a pass that binds its own textures. The medium shading over a Medium (its
    // grid, its tau_sun). The layers' slabs then end where their rays meet the terrain (the
    // frame's depth).
    if (stretch)
        end_.draw({o, frame, noise_shift_, in_stack, noise_.get(), resolved_depth, sampled ? at_samples : nullptr, fog_,
                   shadow_, sun_, light_volume_});
    const bool sun_lookup = sun_ && sun_->ready() && o.shading == geometry::LayerShading::medium;
    // Each program's uniforms and textures (the units are the same for both).
    const auto prepare = [&](const ShaderProgram& q) {
        if (fog_)
            fog_->bind_apply(q);
        bind_terrain_shadow(q, shadow_);
        q.set("u_view_projection", frame.view_projection);
        set_layer_stack_uniforms(q, o, base_->centre, frame.eye, top, under);
        set_eye_in_stack_uniforms(q, in_stack);
        q.set("u_stretch_pass", int(stretch));
        if (stretch) {
            q.set("u_frame_depth", layers_unit_ground_depth);
            q.set("u_target_size", glm::vec2(float(low_width_), float(low_height_)));
            q.set("u_inverse_view_projection", frame.inverse_view_projection);
            glBindTextureUnit(layers_unit_ground_depth, resolved_depth);
        }
        if (sampled) {
            q.set("u_frame_samples", layers_unit_samples);
            q.set("u_sample_count", at_samples->count);
            glProgramUniform2fv(q.id(), q.location("u_sample_offsets"), 8, at_samples->offsets);
            glBindTextureUnit(layers_unit_samples, at_samples->depth);
        }
        q.set("u_atlas", 0);
        q.set("u_heights", 1);
        q.set("u_noise", 2);
        q.set("u_height_rect", height_rect_);
        q.set("u_height_texels", height_texels_);
        q.set("u_opacity", float(o.opacity));
        q.set("u_ground_fade", float(o.ground_fade));
        set_layers_light_uniforms(q, o, frame, noise_shift_);
        q.set("u_medium", int(medium));
        // The volume's own copy of the Medium's grid, after bind_apply: the froxels bind theirs
        // only where they apply fog, and their apply's lookups in these programs do not read it.
        // Per fragment within the distance where the spacing narrows, L0 = divisor r0 ([Thesis]
        // 2.8): there the full-level triangles near the eye span wide angles; per vertex beyond.
        q.set("u_lv_per_fragment", float(reach));
        if (light_volume_)
            light_volume_->bind(q, layers_unit_baked_moments, baked);
        else
            LightVolumeTexture{}.bind(q, layers_unit_baked_moments, false);
        // tau_sun per fragment from the sun volume (before the grid's binding below, which points
        // u_md_grid at the same grid on another unit); without one, the slab above each layer.
        if (sun_lookup)
            sun_->bind(q, layers_unit_sun, sun_march_steps);
        q.set("u_sv_volume", layers_unit_sun + 2);  // its sampler on a unit of its own, bound or not
        q.set("u_sun_lookup", int(sun_lookup));
        q.set("u_sv_direction", sun_march_direction(frame.sun_direction));
        // The Medium's coverage, where the medium shading's fog is (after the baked light's binding
        // of the same grid on the same unit).
        q.set("u_md_extent", int(medium && sun_ && sun_->bind_grid(q, layers_unit_baked_moments + 1)));
        set_partition_uniforms(q, frame);
        q.use();
        glBindTextureUnit(0, atlas_.get());
        glBindTextureUnit(1, heights_.get());
        glBindTextureUnit(2, noise_.get());
    };
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glDisable(GL_CULL_FACE);
    glBindVertexArray(vao_.get());
    // Away from the eye a column holds layers 0..count (layer_column: the spacing narrows, and
    // the count grows past l0, only within L0 = divisor r0 of the eye); the layers above are
    // drawn for the triangles with a vertex nearer than that alone. The instances run over the
    // layers over the eye from the top down, then over those under it from the bottom up
    // (layers.vert); each run is cut where its layers change from every triangle to the near
    // ones: the same fragments in the same order, those skipped had zero opacity.
    const int everywhere = std::min(top, o.count);
    const ShaderProgram* current = &p;
    auto draw = [&](int first_instance, int instances, GLuint indices, GLsizei count) {
        if (instances <= 0 || count <= 0)
            return;
        current->set("u_first_instance", first_instance);
        glVertexArrayElementBuffer(vao_.get(), indices);
        glDrawElementsInstanced(GL_TRIANGLES, count, GL_UNSIGNED_INT, nullptr, instances);
    };
    // Layers 0..top in the order `order` (layers.vert's u_under): those over the eye's layer top
    // down, then those under it bottom up; layers 0..e of the triangles `all`, the rest of `near`.
    const auto run = [&](int order, int e, GLuint all, GLsizei all_count, GLuint near, GLsizei near_count) {
        current->set("u_under", order);
        const int over = top + 1 - order;
        draw(0, top - std::max(order, e + 1) + 1, near, near_count);                 // over: top..e + 1
        draw(top - std::min(e, top), std::min(e, top) - order + 1, all, all_count);  // over: e..order
        draw(over, std::min(order - 1, e) + 1, all, all_count);                      // under: 0..e
        draw(over + e + 1, order - 1 - e, near, near_count);                         // under: e + 1..order - 1
    };
    const auto use = [&](const ShaderProgram& q) {
        prepare(q);
        current = &q;
    };
    const GLuint all = lod_active_ ? lod_indices_.get() : indices_.get();
    const GLsizei all_count = lod_active_ ? lod_count_ : index_count_;
    const GLuint none = 0;
    if (split)
        update_near(eye, reach, flat);
    use(p);
    if (!o.narrowing || top == everywhere) {
        // Without the narrowing every layer covers every triangle. With it but no column within
        // L0 of the eye (the count grows only there), none within the flat radius either: every
        // layer is far, drawn as the cones below, without sorting triangles. Split, the far
        // triangles first, then those within L0 of the eye: nearer along every ray.
        const int order = o.narrowing && under > 0 ? top + 1 : (o.narrowing ? 0 : under);
        if (!split) {
            run(order, top, all, all_count, all, all_count);
        } else {
            run(order, top, far_rest_.get(), far_rest_count_, far_rest_.get(), far_rest_count_);
            use(near_program);
            run(order, top, near_all_.get(), near_all_count_, near_all_.get(), near_all_count_);
        }
    } else {
        // The narrowing spaces the layers by r0 L / L0 within L0 of the eye, down to its floor
        // T0 / max_count within L0 count / max_count: there the layers are flat, and a ray from
        // the eye meets those over it from the lowest (top first) and those under it from the
        // highest (bottom first). Further out each layer is a cone rising away from the eye, which
        // every ray from an eye over the base meets from the highest down (bottom first), and from
        // one under the base from the lowest up. The flat triangles are nearer along every ray
        // from the eye: the cones are drawn first, then the flat part; split, the far cones before
        // the near ones.
        update_near(eye, reach, flat);
        const int cones = under > 0 ? top + 1 : 0;
        if (!split) {
            run(cones, everywhere, all_rest_.get(), all_rest_count_, near_rest_.get(), near_rest_count_);
        } else {
            run(cones, everywhere, far_rest_.get(), far_rest_count_, none, 0);
            use(near_program);
            run(cones, everywhere, near_rest_.get(), near_rest_count_, near_rest_.get(), near_rest_count_);
        }
        run(under, top, flat_.get(), flat_count_, flat_.get(), flat_count_);
    }
    glVertexArrayElementBuffer(vao_.get(), indices_.get());
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
}

void LayersPass::update_near(const glm::dvec3& eye, double reach, double flat)
{
    if (eye == near_eye_ && reach == near_reach_ && flat == near_flat_ && all_rest_)
        return;
    const std::vector<std::uint32_t>& all = drawn_triangles();
    // 1 % more than L0: float and double agree about the columns at its edge.
    const double reach2 = (1.01 * reach) * (1.01 * reach), flat2 = flat * flat;
    std::vector<char> near(base_->position.size()), flat_at(base_->position.size());
    for (std::size_t v = 0; v < near.size(); ++v) {
        const glm::dvec3 d = base_->position[v] - eye;
        near[v] = glm::dot(d, d) < reach2;
        flat_at[v] = glm::dot(d, d) < flat2;
    }
    std::vector<std::uint32_t> flat_list, near_rest, all_rest, far_rest, near_all;
    for (std::size_t t = 0; t + 2 < all.size(); t += 3) {
        const std::uint32_t a = all[t], b = all[t + 1], c = all[t + 2];
        const bool is_near = near[a] || near[b] || near[c];
        if (is_near || flat_at[a] || flat_at[b] || flat_at[c])
            near_all.insert(near_all.end(), {a, b, c});
        if (flat_at[a] || flat_at[b] || flat_at[c]) {
            flat_list.insert(flat_list.end(), {a, b, c});
            continue;
        }
        all_rest.insert(all_rest.end(), {a, b, c});
        (is_near ? near_rest : far_rest).insert((is_near ? near_rest : far_rest).end(), {a, b, c});
    }
    const auto upload = [](Buffer& buffer, GLsizei& count, const std::vector<std::uint32_t>& indices) {
        buffer = make_buffer();
        glNamedBufferStorage(buffer.get(), GLsizeiptr(std::max<std::size_t>(indices.size(), 1) * sizeof(std::uint32_t)),
                             indices.empty() ? nullptr : indices.data(), 0);
        count = GLsizei(indices.size());
    };
    upload(flat_, flat_count_, flat_list);
    upload(near_rest_, near_rest_count_, near_rest);
    upload(all_rest_, all_rest_count_, all_rest);
    upload(far_rest_, far_rest_count_, far_rest);
    upload(near_all_, near_all_count_, near_all);
    near_eye_ = eye;
    near_reach_ = reach;
    near_flat_ = flat;
}

}  // namespace kiri::render::detail
