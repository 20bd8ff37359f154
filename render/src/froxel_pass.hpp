#pragma once
// Froxel volumetric fog ([Wronski14], with [Hillaire15]'s energy-conserving integration and
// fog-aware slicing; docs/froxel.md). A frame:
//   prepare   is the fog in view (the renderer brought the sun's shadow map of the terrain up
//             to date before); then the scene is drawn and resolved, and
//   update    only when the view, the sun or the fog changed, and once more when a moving view
//             stops: tiles (the depths each screen tile's slices span, from the frame's depth
//             and the rasterised shell, froxel_tile_bounds.hpp), density (extinction per
//             froxel), lighting (J: the sun through the terrain's ESM and the fog, sky ambient,
//             Henyey-Greenstein; one jittered sample a froxel), temporal (reprojected, clamped
//             history of J; a still runs its first samples through it at once),
//             integrate (front to back through the slices), classify (per tile: may the
//             apply read the volume, or must the pixels around it march their own rays);
//   apply     every frame, the fog on the resolved frame (froxel_apply.comp).
#include <array>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "frame_context.hpp"
#include "froxel_medium.hpp"
#include "froxel_shell.hpp"
#include "froxel_tile_bounds.hpp"
#include "froxel_volume_key.hpp"
#include "light_volume_texture.hpp"
#include "kiri/geometry/volume/froxel_options.hpp"
#include "kiri/render/renderer.hpp"
#include "pass_timer.hpp"
#include "render_targets.hpp"
#include "shader_program.hpp"
#include "shadow_map_pass.hpp"
#include "staged_read.hpp"

namespace kiri::geometry {
class Medium;
}

namespace kiri::render::detail {

class TerrainPass;
class SunVolume;

//! froxel_light.glsl's uniforms for a frame: the sun (as the marches take its direction), the sky,
//! the air, each medium's albedo and anisotropy (the Medium, null: none; the height fog) and the
//! lighting model, the fog's own shadow on or off. The froxels and the particles' near field light
//! the fog with the one code.
void set_medium_light_uniforms(const ShaderProgram& p, const FrameContext& frame, const geometry::Medium* medium,
                               const geometry::HeightFog& haze, bool fog_shadows);

class FroxelPass {
public:
    FroxelPass();
    ~FroxelPass();
    //! medium may be null (height fog alone); it is kept by pointer.
    void set_fog(const geometry::Medium* medium, const geometry::FroxelOptions& options);
    void clear();
    bool enabled() const { return enabled_; }
    //! Grows (lo, hi) to hold the Medium (for the frame's near and far planes).
    void extend_bounds(glm::dvec3& lo, glm::dvec3& hi) const;
    //! Before the scene is drawn: whether the fog is in view; the sun's shadow map of the
    //! terrain its lighting reads (null: no terrain shadows), kept by pointer for the frame.
    void prepare(const FrameContext& frame, const ShadowMapPass* shadow);
    //! The sun volume the lighting reads tau_sun from (null, or FroxelOptions::sun_volume off:
    //! the lighting marches it), kept by pointer for the frame.
    void set_sun_volume(const SunVolume* sun) { sun_ = sun; }
    //! The baked multiple scattering the lighting adds (the Medium's model `baked`; null or not
    //! ready: single scattering). This frame's, the renderer's.
    void set_light_volume(const LightVolumeTexture* volume) { light_volume_ = volume; }
    //! The Medium drawn (null: the height fog alone).
    const geometry::Medium* medium() const { return medium_; }
    const geometry::FroxelOptions& options() const { return options_; }
    //! Renderer::set_froxel_resolution.
    void set_resolution(double scale);
    using FrameSamples = detail::FrameSamples;
    //! After the resolve: the volume's passes, when this frame needs them (depth: the frame's;
    //! samples: the frame's, which the apply will read, or null).
    void update(const FrameContext& frame, const TerrainPass& terrain, GLuint depth_texture,
                const FrameSamples* samples = nullptr);
    //! The fog on the resolved frame (colour: RGBA16F, read and written); where a pixel's
    //! samples see different fog (two surfaces, or one fogged unevenly), each side its own
    //! (froxel_edges.comp).
    void apply(const FrameContext& frame, GLuint color_texture, GLuint depth_texture, const FrameSamples& samples);
    //! froxel_apply.glsl's uniforms and textures on a program linking froxel_common.glsl,
    //! froxel_medium.glsl and froxel_apply.glsl (for layers and particles: froxel_fog(world)).
    void bind_apply(const ShaderProgram& program) const;
    //! The fog the last frame's pixels received at the terrain's depth at their centres.
    FogBuffer read_fog(const FrameContext& frame, const TerrainPass& terrain);
    const FroxelStats& stats() const { return stats_; }
    //! The timings of the passes that ran this frame (read after the frame finished).
    void append_timings(std::vector<PassTime>& out) const;

private:
    struct Volumes;
    std::unique_ptr<Volumes> v_;
    // A program in variants with the height fog's code (FROXEL_HEIGHT_FOG 1) or without, and
    // with the baked light's lookup (LIGHT_VOLUME 1, a Medium whose model is `baked`) or without:
    // llvmpipe runs a branch's code whether any lane takes it or not, and the height fog's code,
    // never run in a scene without one, made the apply 1.7 times as slow; the baked light's took
    // the default still's marches and split pixels 80-90 ms each. Each built on first use
    // (program()).
    class Variants {
    public:
        explicit Variants(std::vector<std::string_view> files) : files_(std::move(files)) {}
        const ShaderProgram& get(bool height_fog, bool light_volume);

    private:
        std::vector<std::string_view> files_;
        std::unique_ptr<ShaderProgram> programs_[4];
    };
    //! The variant of `v` for this scene's height fog and Medium.
    const ShaderProgram& program(Variants& v) { return v.get(options_.height_fog.enabled(), baked_light()); }
    ShaderProgram fog_tiles_, density_;
    Variants lighting_;
    ShaderProgram temporal_, accumulate_, opaque_;
    Variants integrate_, classify_, pixels_, upsample_;
    ShaderProgram apply_program_, readback_, edges_, lookup_;
    // The fog-aware apply's fog per pixel of a frame (froxel_pixel_fog.cpp): the grids of
    // samples and what their points are judged by, the fog, the lists of the points that march
    // (one per refinement) and their counts, the frame before its fog.
    //! The grids of samples, coarsest first: every 8th pixel of every 8th row, then every 4th and
    //! 2nd (froxel_frame.glsl's frame_grid), each refined from the one before; then every pixel.
    static constexpr std::array<int, 3> sample_spacings{8, 4, 2};
    struct PixelFog {
        int width = 0, height = 0;
        std::array<Texture, sample_spacings.size()> samples;  // the grids at sample_spacings
        std::array<Texture, sample_spacings.size()> info;     // their points' frame_point_info
        Texture fog, background;
        // The points each refinement (spacings 4, 2, 1) left to march, and its counts.
        std::array<Buffer, sample_spacings.size()> lists;
        Buffer lookups;  // a refinement's points that read the volume (froxel_lookup.comp)
        // Pixels whose samples see two surfaces, or one fogged unevenly (froxel_edges.comp): split
        // (1 where their samples march), bounds of their rays' stretch of the shell, the mean of
        // their samples' fog over the resolved colour; the list of them.
        Texture split, split_ray, split_fog;
        Buffer split_list;
        bool splits_run = false;  // the last frame split pixels
        void resize(int width, int height);
        //! The last run's pixels that marched, that took their samples' mean, that were split, and
        //! of those the ones split by their fog on one surface.
        struct Counts {
            int marched = 0, upsampled = 0, split = 0, fog_split = 0;
        };
        Counts read_counts() const;
        mutable StagingBuffer staging;  // read_counts' (every frame's counts)
    };
    PixelFog applied_;  // the apply's; read_fog runs over it again, judged over its background
    //! Every pixel's (in-scattered radiance, transmittance) into out.fog, over the frame's depth,
    //! judged over its colour (RGBA16F, before the fog; 0: out.background's, the last one copied).
    void run_pixel_fog(const FrameContext& frame, GLuint depth_texture, GLuint color_texture, PixelFog& out,
                       const FrameSamples* samples = nullptr);
    //! The apply's pixels whose samples see different fog, each sample's own ray marched to its
    //! own surface, their mean (out.split, split_ray, split_fog). Whether it ran.
    bool run_splits(const FrameContext& frame, GLuint depth_texture, const FrameSamples& samples, PixelFog& out);
    //! The split pixels' inputs (their rays' bounds, the frame's samples where given) and the
    //! tiles on the units the pixels' program declares them: bound alike in each of its stages.
    void bind_stage_inputs(const PixelFog& out, const FrameSamples* samples) const;
    //! The classification's last test: the tiles it left undecided (w = -1) march their central
    //! pixel's ray in the pixels' program (froxel_pixels.comp's u_stage 2), and march where it
    //! and the volume's lookup differ by more than `missed`.
    void run_tile_rays(const FrameContext& frame, GLuint depth_texture, const FrameSamples* samples, float missed);
    //! The list of those tiles, emptied and bound for the classification to fill.
    void bind_tile_rays();
    Buffer tile_rays_;
    int tile_rays_capacity_ = 0;
    //! A program of froxel_frame.glsl's pixels (the march's, the grids') bound for the frame, its
    //! grid at `spacing`, the frame's depth on the unit u_depth reads.
    void bind_pixel_program(const ShaderProgram& program, const FrameContext& frame, int spacing) const;
    std::unique_ptr<ShaderProgram> depth_program_;  // built on first use
    FroxelMedium medium_gpu_;
    FroxelTileBounds tile_bounds_;
    const ShadowMapPass* shadow_ = nullptr;             // this frame's, the renderer's
    const SunVolume* sun_ = nullptr;                    // this frame's, the renderer's
    const LightVolumeTexture* light_volume_ = nullptr;  // this frame's, the renderer's
    int shadow_version_ = -2;                           // its updates() when the volume was lit (-1: none)
    ShellMesh shell_;  // the whole shell: its inside test, and what a full-resolution frame rasterises
    // Coarser shells for the froxel resolution's steps (1/2, 1/4, 1/8: set_resolution), built on
    // first use: a frame drawn small rasterises as many blocks as it has pixels for.
    std::array<std::optional<ShellMesh>, 3> coarse_shells_;
    int drawn_shell_ = 0;  // which the tile bounds hold: 0 the whole shell, k the 2^-k step's
    void use_shell_for_resolution();
    // A frame drawn at a share r of the still's resolution (set_resolution: the preview's moving
    // frames, whose pixels are 1/r times as wide and whose volume is as coarse) marches r^(1/3)
    // of pixel_steps and takes its samples' mean within r^(-2/3) times the tolerance: at the
    // floor (1/8) half the steps and four times the tolerance, the apply 66 -> 33 ms of a
    // 160x90 frame whose error against the reference went 5.4 -> 5.9 % (the still's 0.8 %).
    int marched_steps() const;
    float upsample_tolerance() const;
    //! The Medium's model is `baked`: its multiple scattering read from the light volume.
    bool baked_light() const
    {
        return medium_ && medium_->options().multiple_scattering == geometry::MultipleScattering::baked;
    }
    const geometry::Medium* medium_ = nullptr;
    geometry::FroxelOptions options_;
    double resolution_ = 1.0;  // of the options' tiles across and down
    bool enabled_ = false, visible_ = false, apply_ = false;
    FroxelTileBounds::Mode mode_ = FroxelTileBounds::Mode::standard;
    bool shell_ok_ = false;  // the shell's per-pixel depths are valid this frame
    // The frame the volume was built for, and the one before (reprojection).
    struct View {
        glm::mat4 view_projection{1.0f};
        glm::vec3 eye{0.0f}, forward{0.0f, 1.0f, 0.0f}, right{1.0f, 0.0f, 0.0f}, up{0.0f, 0.0f, 1.0f};
        float near = 1.0f, far = 2.0f;
    } view_, previous_;
    std::optional<FroxelVolumeKey> key_;
    std::optional<FroxelVolumeLayout> layout_;
    int frame_index_ = 0, current_ = 0;
    bool history_valid_ = false;
    bool converged_ = false;     // the volume is final for its view (a still's, or without the filter)
    glm::vec3 light_[3]{};       // sun direction, radiance, ambient of the last run
    mutable FroxelStats stats_;  // the apply's counts read with the timings, after the frame
    bool classified_ = false;    // the tiles say where the apply reads the volume (fog-aware)
    int applied_pixels_ = 0;
    std::vector<PassTimer> timers_;  // one per stage, in stage order

    bool visible(const FrameContext& frame) const;
    void bind_layout(const ShaderProgram& program) const;
    // The update's passes, in order; each times itself.
    void run_passes(const FrameContext& frame, GLuint depth_texture, bool still, const FrameSamples* samples);
    struct Jitter {
        glm::vec3 froxel{0.5f};  // the sample's position in its froxel
        float sun = 0.5f;        // the start of its sun march
    };
    static Jitter halton_jitter(int index);
    //! The frame's view becomes the volume's (the last one is kept for reprojection).
    void advance_view(const FrameContext& frame);
    void run_tiles(const FrameContext& frame, GLuint depth_texture);
    void run_density();
    void list_fog_tiles();  // the tiles with fog, for the passes over their froxels alone
    void run_lighting(const FrameContext& frame, const Jitter& jitter);
    //! A still's k-th lighting sample into the mean of the first k (froxel_accumulate.comp).
    void run_accumulate(int history, bool history_valid, int into, float weight);
    //! The lighting just run blended with resolved[history] (seen from `from`, its tiles
    //! tiles[history]; the history's weight `weight`) into resolved[into].
    void run_temporal(int history, const View& from, bool history_valid, int into, float weight);
    void run_integrate(const FrameContext& frame);
    //! Per tile: may the apply read the volume, or must the pixels around it march?
    void run_classify(const FrameContext& frame, GLuint depth_texture, const FrameSamples* samples);
    //! froxel_light.glsl's uniforms and textures (the sun volume, the terrain's shadow map, the
    //! baked light) on the lighting pass or a program that marches pixels (froxel_march.glsl).
    void bind_light(const ShaderProgram& program, const FrameContext& frame) const;
};

}  // namespace kiri::render::detail
