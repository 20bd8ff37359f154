#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "density_ratio_texture.hpp"
#include "frame_context.hpp"
#include "froxel_pass.hpp"
#include "kiri/geometry/particles/particles.hpp"
#include "kiri/render/attenuation.hpp"
#include "kiri/render/renderer.hpp"
#include "particle_light.hpp"
#include "shader_program.hpp"

namespace kiri::render::detail {

class LightVolumeTexture;
class SunVolume;

//! Particle clouds: the attenuation buffer (rebuilt only when the sun, the particles or the
//! buffer's options change) and the billboards, sorted back to front on the CPU when the eye
//! moves, drawn into their own float target with the terrain's depth for soft edges, then
//! composited over the resolved frame.
class ParticlesPass {
public:
    ParticlesPass();
    //! Keeps the cloud by reference; uploads it when its contents changed. Returns true if it did.
    bool set_particles(const geometry::ParticleCloud& cloud, const ParticleStyle& style);
    void clear();
    bool has_particles() const { return cloud_ != nullptr && count_ > 0; }
    void extend_bounds(glm::dvec3& lo, glm::dvec3& hi) const;
    //! Draws over `resolved_fbo`. Returns whether the attenuation buffer was rebuilt. With the
    //! frame's samples (their depth; their colour where the frame below is still their mean), a
    //! small still of the particles alone, standing for the Medium (match_medium), is drawn along
    //! each sample's ray (at_samples).
    bool draw(const FrameContext& frame, unsigned resolved_fbo, unsigned resolved_depth,
              const struct FrameSamples* samples = nullptr);
    //! Whether a frame of this size is drawn at its samples: a still of the particles alone
    //! (not under froxel fog) of at most max_pixels_at_samples pixels, the views bench's and the
    //! tests' size, where a pixel spans a thread of fog or its shore (docs/particles.md, "A
    //! still's particles at each sample"). Larger frames draw at each pixel's centre.
    bool at_samples(const FrameContext& frame, const struct FrameSamples* samples) const;
    static constexpr int max_pixels_at_samples = 320 * 180;
    const AttenuationBuffer& buffer() const { return buffer_; }
    const ParticleLight& light() const { return light_; }
    //! For the frame: froxel fog to read at each billboard's depth (null: none; drawn after its
    //! apply), the sun's shadow map of the terrain (null: no terrain shadows) and the sun volume
    //! (the Medium's optical depth towards the sun, which each particle's light is measured
    //! against; null: the fixed share).
    void set_fog(const FroxelPass* fog, const ShadowMapPass* shadow, const SunVolume* sun = nullptr)
    {
        fog_ = fog;
        shadow_ = shadow;
        sun_ = sun;
    }
    //! For frames drawn at `scale` of the still's size (the preview while the view moves): every
    //! k-th billboard, k the largest power of two no larger than 1 / (2 scale) (1 from a half
    //! on, 4 at an eighth), drawn sqrt(k) times as wide with the particle's own optical depth, so
    //! the fog keeps its optical mass and its cover while k times fewer billboards are set up (a
    //! software rasteriser pays for each, however few pixels it covers). Default 1.
    void set_resolution(double scale);
    //! The baked multiple scattering (null or not ready: none), for the frame.
    void set_light_volume(const LightVolumeTexture* volume) { light_volume_ = volume; }
    std::size_t count() const { return has_particles() ? count_ : 0; }
    //! Of the last draw: billboards drawn at the near resolution, all billboards drawn, fragments
    //! blended (all targets).
    int last_near_count() const { return last_near_; }
    int last_drawn_count() const { return int(order_cpu_.size()); }
    //! Read after the frame has finished (the query's result waits for the GPU): reading it in
    //! the pass would stall the CPU there on a GPU, in the middle of the frame.
    std::uint64_t last_fragments() const;
    bool last_light_rebuilt() const { return last_light_rebuilt_; }

private:
    ShaderProgram composite_;
    //! The billboards' program, reading the froxel fog (froxel_apply.glsl) or not, without the
    //! baked light (light_volume_preamble), with it per particle, or with it per fragment too (the
    //! billboards around the eye), reading the own gains from the table alone or computing them
    //! where it is missing, weighting the balls by the density ratio or not (match_medium), at
    //! each pixel's centre or at its samples: [fog][baked][table][ratio][samples], each built on
    //! first use.
    std::unique_ptr<ShaderProgram> programs_[2][3][2][2][2];
    //! The near field's march (particles_near.frag), without the baked light and with it.
    std::unique_ptr<ShaderProgram> near_programs_[2];
    //! The near field's reach for this frame: metres along each ray, 0 where there is none (under
    //! froxel fog, without a Medium, or with the eye farther than it from every ball).
    double near_field_reach(const FrameContext& frame) const;
    void draw_near_field(const FrameContext& frame, double reach, bool baked, unsigned resolved_fbo,
                         unsigned resolved_depth);
    //! The baked light each particle's billboard takes towards the eye (particle_baked.comp), read
    //! again when the order or the volume changed.
    std::unique_ptr<ShaderProgram> baked_program_;
    Buffer baked_lights_;
    std::size_t baked_capacity_ = 0;
    // What the baked lights were read for: the order's sort and the volume's upload (-1: none).
    int baked_sort_ = -1, baked_volume_updates_ = -1;
    //! Of the billboards sorted far to near, the first whose ball can hold the eye (its centre
    //! within the largest radius of it in depth).
    std::size_t around_first() const;
    void update_baked_lights(const FrameContext& frame);
    const LightVolumeTexture* light_volume_ = nullptr;
    const FroxelPass* fog_ = nullptr;
    const ShadowMapPass* shadow_ = nullptr;
    const SunVolume* sun_ = nullptr;
    VertexArray vao_;
    AttenuationBuffer buffer_;
    ParticleLight light_;        // what each billboard's light needs of its particle alone
    DensityRatioTexture ratio_;  // the Medium over the balls' sum (particles alone)
    const geometry::ParticleCloud* cloud_ = nullptr;
    std::uint64_t uploaded_hash_ = 0;
    std::size_t count_ = 0;
    std::size_t share_ = 1;  // every share_-th billboard is drawn (set_resolution)
    ParticleStyle style_;
    Buffer order_;                          // indices into the buffer's particle SSBO, back to front
    Buffer quad_indices_;                   // 4q, 4q + 1, 4q + 2, 4q + 2, 4q + 1, 4q + 3 for each billboard q
    std::vector<std::uint32_t> order_cpu_;  // the billboards in view, far to near (sort)
    std::vector<float> keys_;
    glm::vec3 sorted_eye_{1e30f}, sorted_forward_{0.0f};
    glm::dmat4 sorted_projection_{0.0};
    int sorts_ = 0;  // times the order was made
    glm::dvec3 lo_{0.0}, hi_{0.0};
    double smallest_radius_ = 0.0, largest_radius_ = 0.0;
    Framebuffer fbo_, near_fbo_, around_fbo_;
    // The near target: near_scale_ times coarser a side, bilinear; the target of the billboards
    // around the eye (around_first) twice as coarse again: each spans the whole screen, and with
    // the baked light reads it at every fragment.
    Texture color_, near_color_, around_color_;
    // Samples 1..3's blends of a still drawn at its samples (color_ holds sample 0's).
    Texture sample_colors_[3];
    // The near field (particles_near.frag), at the near target's resolution or finer.
    Framebuffer near_field_fbo_;
    Texture near_field_color_;
    glm::ivec2 near_field_size_{0};
    int width_ = 0, height_ = 0, near_scale_ = 0;
    bool target_samples_ = false;
    Query fragments_query_;
    int last_near_ = 0;
    bool last_light_rebuilt_ = false;
    mutable std::uint64_t last_fragments_ = 0;
    mutable bool fragments_pending_ = false;
    void ensure_target(int width, int height, int near_scale, bool at_samples);
    //! The billboards whose particle can reach a pixel of the frame, far to near, into order_.
    void sort(const FrameContext& frame);
    //! Of the billboards sorted far to near, the first one drawn at the near resolution.
    std::size_t near_first(const FrameContext& frame) const;
};

}  // namespace kiri::render::detail
