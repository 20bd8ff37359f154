#pragma once
//! \file renderer.hpp
//! The frame renderer: owns the GPU resources of a scene and draws it into an offscreen
//! framebuffer. Resources are uploaded once and rebuilt only when their inputs change.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "kiri/render/attenuation.hpp"
#include "kiri/render/camera.hpp"
#include "kiri/render/image.hpp"
#include "kiri/render/overlay_mesh.hpp"

namespace kiri::geometry {
class Terrain;
class Medium;
struct LayerBase;
struct LayerOptions;
struct FroxelOptions;
struct FogPartition;
struct LightVolume;
struct HeightFog;
}  // namespace kiri::geometry

namespace kiri::render {

struct SunLight {
    glm::dvec3 direction{0.5, -0.3, 0.6};  //!< towards the sun (normalised by the renderer)
    glm::dvec3 color{1.0, 0.96, 0.9};
    double intensity = 3.0;
    glm::dvec3 ambient{0.25, 0.3, 0.38};
    //! false: no sky light at all (`kiri render --no-sky`): no ambient, a black sky without the
    //! sun's glow, for comparisons with renderers set up in a black world.
    bool sky = true;
    //! true: the terrain and the ground beyond it drawn black (`kiri render --black-ground`); they
    //! still hide and shadow, so the picture is the fog's own light, as the CPU renderers'
    //! black ground and the path tracer's PathGround::black draw it.
    bool black_ground = false;
    //! The terrain's shadows from the sun: one exponential shadow map a frame ([Annen08]) that
    //! every pass lit by the sun reads (the terrain, the froxels, the layers, the particles),
    //! as the CPU reference shadows every point it lights (FogLighting::terrain_shadows).
    bool terrain_shadows = true;
    int shadow_map_size = 1024;  //!< texels a side
    double esm_sharpness = 4.0;  //!< the ESM exponent per texel of light depth
};

//! How particle clouds are drawn (docs/particles.md).
struct ParticleStyle {
    AttenuationOptions buffer;  //!< the attenuation buffer's resolution, format and frame
    double soft_edge = 0.0;     //!< metres over which a billboard also fades in front of the terrain (0: none)
    //! Billboards near the eye, whose every radius spans at least `near_pixels` pixels, are
    //! drawn into a target `near_scale` times coarser a side (1: every billboard at full
    //! resolution) and laid over the others: they are smooth at that scale, and they are most of
    //! the fragments when the eye is in the fog.
    int near_scale = 2;
    double near_pixels = 6.0;
    //! Billboards whose particle lies wholly outside the view are not drawn (the picture is the
    //! same; false draws every one, for tests and benches).
    bool cull_outside_view = true;
    //! The near field, with the particles alone (not under froxel fog): within `near_field`
    //! times the largest radius of the eye, the Medium itself is marched along each ray in
    //! `near_field_steps` steps and the billboards draw their balls from there on (a few balls
    //! around the eye are each a blot over a large part of the frame). 0: none.
    double near_field = 2.5;
    int near_field_steps = 32;
    //! With the particles alone and a Medium they stand for, each ball's density along a ray is
    //! weighted by the Medium's extinction over the balls' summed density there
    //! (geometry::density_ratio_grid): the balls together draw the Medium.
    bool match_medium = true;
};

struct PassTime {
    std::string pass;
    //! The device's time of the pass: a GL timer query on a GPU; on a software rasteriser
    //! (llvmpipe), whose queries do not time passes, the wall time from an idle device through
    //! the pass to an idle device (render/src/pass_timer.hpp).
    double gpu_ms = 0.0;
    double cpu_ms = 0.0;  //!< the time the pass's commands took to issue
};

//! What the froxel fog did in a frame.
struct FroxelStats {
    bool enabled = false;  //!< set_froxel_fog was called
    bool visible = false;  //!< the fog was in view (fog off-screen costs nothing)
    bool updated = false;  //!< its passes ran this frame (not for a static view and fog)
    //! The volume is final for this view: a still's (its lighting's jittered samples taken at
    //! once), or one without temporal filtering. The same view again reruns nothing.
    bool converged = false;
    int updates = 0;     //!< frames whose passes ran since set_froxel_fog
    glm::ivec3 size{0};  //!< the volume's froxels across, down and in depth (set_froxel_resolution)
    //! The last apply: its pixels; those that marched their own rays (fog-aware: where the
    //! volume's slices do not resolve the fog around them) instead of reading the volume; and
    //! those that took the mean of the marched half-resolution samples around them
    //! (FroxelOptions::upsample).
    int applied_pixels = 0, marched_pixels = 0, upsampled_pixels = 0;
    //! Pixels whose samples saw different fog, each sample's own ray marched to its own surface:
    //! two surfaces (a ridge against the fog behind it), or one fogged unevenly
    //! (`fog_split_pixels` of them: a thread of fog narrower than the pixel, the fog's top meeting
    //! a slope).
    int edge_pixels = 0, fog_split_pixels = 0;
};

//! Float pixels, rows top to bottom: the fog a frame's pixels received (froxel fog).
struct FogBuffer {
    int width = 0, height = 0;
    std::vector<float> rgba;   //!< in-scattered radiance (linear RGB) and transmittance per pixel
    std::vector<float> depth;  //!< view depth of the surface per pixel; -1 for sky
};

struct FrameStats {
    //! sky, terrain, layers, resolve, tonemap, then the particles', the overlays' and the froxel
    //! passes that ran. They do not overlap (the particles' "attenuation" build is a part of
    //! "particles"): their device times add up to no more than frame_ms.
    std::vector<PassTime> passes;
    double frame_ms = 0.0;
    int uploads = 0;             //!< GPU resources (re)built during this frame
    int shadow_map_updates = 0;  //!< the sun's shadow map's builds so far (kept while sun and terrain stay)
    //! The sun volume's builds so far (kept while the sun, the Medium and its time stay): the
    //! fog's optical depth towards the sun that the froxels and the layers read.
    int sun_volume_updates = 0;
    int layers = 0;             //!< fog layers above the base drawn (0: none, or culled off-screen)
    int terrain_triangles = 0;  //!< the grid's triangles drawn (set_terrain_resolution's level)
    //! The terrain mesh's vertices, and those in the fog's shade whose cells' fragments read the
    //! finer map of the sun's optical depth (where the shade bends within a cell).
    int terrain_vertices = 0, refined_shade_vertices = 0;
    int layer_triangles = 0;               //!< the base's triangles drawn for each layer (the level of detail's)
    int particles = 0;                     //!< particles in the cloud
    int particles_drawn = 0;               //!< billboards drawn: the particles that reach the view
    int attenuation_rebuilds = 0;          //!< attenuation buffer builds during this frame (0 when nothing changed)
    int particle_light_rebuilds = 0;       //!< builds of the billboards' per-particle light during this frame
    int near_particles = 0;                //!< billboards drawn at the coarser near resolution
    std::size_t particle_light_bytes = 0;  //!< the per-particle light: records and the gain table
    //! Fragments the billboards blended (GL_SAMPLES_PASSED: not discarded), near ones at the
    //! near target's resolution.
    std::uint64_t particle_fragments = 0;
    FroxelStats froxel;
};

class Renderer {
public:
    //! A GL context must be current.
    Renderer();
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    //! The terrain to draw (kept by reference: it must outlive the renderer's use of it).
    //! Re-uploads only when the terrain, the exaggeration or the surround changed. `surround`:
    //! the ground beyond the DEM's edge (kiri/geometry/terrain/ground.hpp); false: the bare tile.
    //! The first terrain, set before anything else, fixes origin().
    void set_terrain(const geometry::Terrain& terrain, double exaggeration = 1.0, bool surround = true);
    void set_sun(const SunLight& sun);
    //! The fog the sun shines through, for every renderer's tau_sun (the sun volume,
    //! docs/medium.md): the Medium (kept by pointer: it must outlive the renderer's use of it;
    //! null: none) and the height fog. Until it is called (or after clear_sun_medium), the
    //! froxel fog's Medium and height fog. Without a Medium the layers take the slab above each
    //! layer and the froxels march the sun's path.
    void set_sun_medium(const geometry::Medium* medium, const geometry::HeightFog& haze);
    void clear_sun_medium();
    //! The baked multiple scattering (geometry::bake_light_volume for this sun and fog) that the
    //! renderers add where the Medium's model is `baked` (medium.multiple_scattering,
    //! docs/medium.md), and the Medium it was baked for, whose columns its cells follow (kept by
    //! pointer: it must outlive the renderer's use of it); null: none, and `baked` draws single
    //! scattering. Uploaded when it is another volume or Medium; the volume is kept (shared).
    void set_light_volume(std::shared_ptr<const geometry::LightVolume> volume, const geometry::Medium* medium);
    //! The fog's layer stack over the terrain (base kept by reference: it must outlive the
    //! renderer's use of it). Uploads only when the base changed; options apply every frame.
    void set_layers(const geometry::LayerBase& base, const geometry::LayerOptions& options);
    void clear_layers();
    //! Resolution of the layer pass relative to the frame, clamped to [1/8, 1]: the layers are
    //! drawn into their own half-float target and composited with depth-aware upsampling
    //! (default 0.5, a quarter of the fragments; the fog is smooth, so the picture barely
    //! changes: `kiri bench --stage layers`). multisampled (scale 1 only) draws them straight
    //! into the 8-bit multisampled frame instead, the plain way.
    void set_layer_resolution(double scale, bool multisampled = false);
    //! Combined mode (docs/combined.md): the layers, the froxels and the particles each draw
    //! their share of the one Medium (geometry/fog_partition.hpp); empty: each draws all of it.
    //! The particles' share is chosen when they are sampled (sample_particles' HeightShare).
    void set_fog_partition(const std::optional<geometry::FogPartition>& partition);
    //! A particle cloud lit through the 3D attenuation buffer, drawn as billboards over the
    //! terrain and the layers (kept by reference: it must outlive the renderer's use of it).
    //! Uploads only when the particles changed; the buffer is rebuilt on the next frame only when
    //! the particles, the sun or style.buffer changed.
    void set_particles(const geometry::ParticleCloud& cloud, const ParticleStyle& style = {});
    void clear_particles();
    //! The particles' attenuation buffer (its grid, memory, build count and time).
    const AttenuationBuffer& attenuation() const;
    //! Froxel volumetric fog (docs/froxel.md) of `medium` (kept by pointer: it must outlive the
    //! renderer's use of it; null for the options' height fog alone), drawn over the terrain and
    //! the sky. The passes rerun only when the view, the sun or the fog (e.g. its time) change.
    //! The terrain's shadows are the sun's shadow map (SunLight::terrain_shadows, its size and
    //! sharpness; SceneRendering::sun copies the options' keys there): options.terrain_shadows
    //! only says whether the froxels' lighting reads it.
    //! \throw kiri::InputError for options out of range.
    void set_froxel_fog(const geometry::Medium* medium, const geometry::FroxelOptions& options);
    void clear_froxel_fog();
    //! The terrain's grid drawn at every (1 / scale)-th sample, scale a power of two in [1/8, 1]
    //! (rounded down to one; the grid's border keeps every sample, so the surround meets it
    //! without a crack): for frames drawn small, where a cell of the whole grid is a fraction of
    //! a pixel (the preview while the view moves). The sun's shadow map keeps the whole grid. Default 1.
    void set_terrain_resolution(double scale);
    //! The froxel volume's tiles across and down relative to the options' size, clamped to
    //! [1/8, 1] (at least one tile): a frame drawn at a fraction of its size (the preview while
    //! the view moves) keeps its pixels per tile, and the volume's passes cost that fraction
    //! squared. A change of it rebuilds the volume without history. Default 1.
    void set_froxel_resolution(double scale);
    //! The particles of a frame drawn at `scale` of its size (the preview while the view moves):
    //! every k-th billboard, k the largest power of two no larger than 1 / (2 scale) (1 from a
    //! half on, 4 at an eighth), sqrt(k) times as wide with its optical depth, so the fog keeps
    //! its optical mass and cover. The particles' light is the same. Default 1.
    void set_particle_resolution(double scale);
    //! The froxel fog each pixel of the last frame received at its depth (empty without it).
    FogBuffer read_froxel_fog();
    //! Adds or replaces the overlay mesh `name` (overlay_mesh.hpp), uploaded once here; its
    //! style is kept. \throw kiri::Error naming it when its arrays disagree.
    void set_overlay(const std::string& name, const OverlayMesh& mesh);
    void set_overlay_style(const std::string& name, const OverlayStyle& style);
    void remove_overlay(const std::string& name);

    //! Renders the frame offscreen and waits for it (no read-back): what a frame costs.
    void draw(const Camera& camera, int width, int height);
    //! Copies the last drawn frame into the window's framebuffer (0), scaled to its size.
    void present(int framebuffer_width, int framebuffer_height) const;
    //! Renders a still picture offscreen and reads it back: final for its view (the froxels'
    //! lighting converged; a view that differs from the last frame's draws twice).
    Image render(const Camera& camera, int width, int height);
    //! The last drawn frame's linear radiance, before the tone map (what the fog renderers are
    //! judged on against the CPU reference).
    RadianceImage read_radiance() const;
    //! The last drawn frame's samples before the resolve (its terrain and sky, and what was
    //! drawn multisampled: no froxel fog, no particles), linear: a judge fogs each sample of a
    //! pixel that straddles two surfaces.
    RadianceSamples read_radiance_samples() const;
    const FrameStats& last_stats() const;

    //! Where the coordinates the GPU works in are measured from (render/src/render_origin.hpp):
    //! (0, 0, 0) unless the first terrain's centre lies over 65 km from the world's origin, then
    //! that centre to the kilometre, so that float keeps the scene's detail (a scene near 1e7 m
    //! draws as it would near the origin). Everything the renderer is given and returns (pick)
    //! is in world coordinates; attenuation()'s grid is in the renderer's.
    glm::dvec3 origin() const;
    //! World position of the surface seen at pixel (x, y) of the last rendered frame (origin at
    //! the top-left, as in Image), read from its depth buffer; empty where only sky was drawn.
    std::optional<glm::dvec3> pick(int x, int y) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace kiri::render
