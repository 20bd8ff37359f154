#pragma once
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "frame_context.hpp"
#include "kiri/geometry/layers/layer_stack.hpp"
#include "layers_end.hpp"
#include "render_targets.hpp"
#include "shader_program.hpp"

namespace kiri::geometry {
struct Heightfield;
}

namespace kiri::render::detail {

class FroxelPass;
class ShadowMapPass;
class SunVolume;
class LightVolumeTexture;

//! The fog's layer stack: the base tessellation uploaded once, drawn as instances (one per
//! layer) with the stack's formulas in the vertex shader, blended over the terrain with the
//! depth test on and depth writes off.
class LayersPass {
public:
    LayersPass();
    //! Uploads the base and its atlas; returns true when it did (a new base).
    bool set_base(const geometry::LayerBase& base);
    void set_options(const geometry::LayerOptions& options) { options_ = options; }
    //! Metres added to (x, y) before the detail noise (MediumDetail::noise_shift): the
    //! renderer's origin, so that the layers' noise stays where it is in the world.
    void set_noise_shift(const glm::dvec2& shift) { noise_shift_ = shift; }
    //! The ground the layers fade into (kept by reference; uploaded on the first draw with
    //! layers, so a scene without fog never pays for it).
    void set_ground(const geometry::Heightfield& heightfield, double exaggeration);
    void clear() { index_count_ = 0; }
    bool has_layers() const { return index_count_ > 0; }
    //! Layers above the base the last draw used (0 when culled or empty).
    int last_layer_count() const { return last_layers_; }
    //! The base's triangles the last draw used for a layer (the level of detail's; 0 when culled).
    int last_triangle_count() const { return last_triangles_; }
    //! Grows (lo, hi) to hold every layer (for the frame's near and far planes).
    void extend_bounds(glm::dvec3& lo, glm::dvec3& hi) const;
    //! False when the stack's bounds lie outside the view (the pass then costs nothing).
    bool visible(const FrameContext& frame) const;
    //! Draws into the bound framebuffer. Returns true when it had to upload the ground first.
    bool draw(const FrameContext& frame);
    //! The fewest texels the reduced target has (320 x 180): a smaller frame draws its layers at
    //! a larger scale, up to its own resolution.
    static constexpr double min_reduced_texels = 320.0 * 180.0;
    //! The scale `draw_reduced` draws a width x height frame at for the setting `scale`.
    static double reduced_scale(double scale, int width, int height);
    //! Draws at reduced_scale(scale, ...) of the frame's resolution into its own target,
    //! depth-tested against the resolved frame's depth, then composites into `resolved_fbo`
    //! with depth-aware upsampling (a quarter of the fragments at scale 0.5). Returns true on
    //! an upload.
    bool draw_reduced(const FrameContext& frame, double scale, unsigned resolved_fbo, unsigned resolved_depth,
                      const FrameSamples& samples);

    //! The froxel fog each layer reads at its own depth (nullptr: none; drawn after its apply)
    //! and the sun's shadow map of the terrain (nullptr: no terrain shadows), for the frame.
    //! The sun volume the medium shading reads tau_sun from (nullptr: the slab above each
    //! layer), for the frame.
    void set_fog(const FroxelPass* fog, const ShadowMapPass* shadow, const SunVolume* sun)
    {
        fog_ = fog;
        shadow_ = shadow;
        sun_ = sun;
    }
    //! The baked multiple scattering the medium shading adds where the layers' optics say
    //! `baked` (it reads the Medium's columns through the sun volume's grid), for the frame.
    void set_light_volume(const LightVolumeTexture* volume) { light_volume_ = volume; }

private:
    ShaderProgram composite_, depth_max_;
    //! The stack's program, with froxel fog (froxel_apply.glsl) or none, and without the baked
    //! light (light_volume_preamble), with it from the vertices, or with it per fragment near the
    //! eye too (`baked` 0, 1, 2), each slab taken along the centre's ray or its samples' (layers.frag's
    //! LAYERS_AT_SAMPLES), each built on first use.
    const ShaderProgram& stack_program(bool froxel_fog, int baked, bool at_samples);
    std::unique_ptr<ShaderProgram> programs_[2][3][2];
    const FroxelPass* fog_ = nullptr;
    const ShadowMapPass* shadow_ = nullptr;
    const SunVolume* sun_ = nullptr;
    const LightVolumeTexture* light_volume_ = nullptr;
    VertexArray empty_vao_;
    Texture noise_;
    // The reduced-resolution target.
    Framebuffer low_fbo_;
    Texture low_color_, low_depth_;
    //! Samples 1..3's blends of the stack where it is drawn along each sample's ray (low_color_
    //! holds sample 0's): at the frame's resolution only, made on first use.
    Texture low_samples_[3];
    int low_width_ = 0, low_height_ = 0;
    bool low_at_samples_ = false;
    void ensure_low(int width, int height, bool at_samples);
    //! Whether there is anything to draw this frame; uploads the ground first if needed.
    bool ready(const FrameContext& frame, bool& uploaded);
    //! target_height: the height in pixels of the target drawn into (the level of detail's scale);
    //! resolved_depth (0: none): the frame's depth, for the fog before the terrain (LayersEnd);
    //! at_samples (null: none): the frame's samples, each slab taken along each one's ray (a target
    //! of the frame's resolution).
    void draw_stack(const FrameContext& frame, int target_height, unsigned resolved_depth = 0,
                    const FrameSamples* at_samples = nullptr);
    LayersEnd end_;
    VertexArray vao_;
    Buffer vertices_, indices_;
    // The layers above `count` fade in only where the eye narrows the spacing ([Thesis] (2.8)):
    // they are drawn for the triangles near it alone (near_eye_ of the eye it was built for).
    // The triangles where the narrowing has reached its floor (within `flat` of the eye, the
    // layers flat there) are drawn apart, last (flat_); near_rest_ and all_rest_ are the near
    // triangles and all of them without those. far_rest_: all_rest_ without the near ones, and
    // near_all_: the near ones with the flat ones (where the baked light is drawn per fragment).
    Buffer flat_, near_rest_, all_rest_, far_rest_, near_all_;
    GLsizei flat_count_ = 0, near_rest_count_ = 0, all_rest_count_ = 0, far_rest_count_ = 0, near_all_count_ = 0;
    glm::dvec3 near_eye_{HUGE_VAL};
    double near_reach_ = -1.0, near_flat_ = -1.0;
    void update_near(const glm::dvec3& eye, double reach, double flat);
    // The level of detail for the last eye (layer_lod.hpp): its triangles replace the base's.
    std::vector<int> lod_levels_;
    std::vector<std::uint32_t> lod_triangles_;
    Buffer lod_indices_;
    GLsizei lod_count_ = 0;
    bool lod_active_ = false;
    int last_triangles_ = 0;
    void update_lod(const FrameContext& frame, int target_height);
    const std::vector<std::uint32_t>& drawn_triangles() const
    {
        return lod_active_ ? lod_triangles_ : base_->triangles;
    }
    Texture atlas_, heights_;
    GLsizei index_count_ = 0;
    geometry::LayerOptions options_;
    glm::dvec2 noise_shift_{0.0};
    const geometry::LayerBase* base_ = nullptr;
    const void* uploaded_base_ = nullptr;
    std::size_t uploaded_base_size_ = 0;
    const geometry::Heightfield* ground_ = nullptr;
    double ground_exaggeration_ = 1.0;
    bool upload_ground();
    const void* uploaded_heights_ = nullptr;
    double uploaded_exaggeration_ = 0.0;
    glm::vec4 height_rect_{0.0f};
    glm::vec2 height_texels_{1.0f};
    int last_layers_ = 0;
    void stack_bounds(glm::dvec3& lo, glm::dvec3& hi) const;
};

}  // namespace kiri::render::detail
