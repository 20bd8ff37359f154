#pragma once
#include <cstdint>
// Any fog renderer's frame of a scene judged against the CPU reference (render::compare_frames):
// the scene's JSON varied per measurement (quality ladders, presets), the reference computed
// once per view, each configuration's cost per frame while the view moves and its error on a
// still picture.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "kiri/geometry/reference/reference_fog.hpp"
#include "kiri/geometry/scene/scene.hpp"
#include "kiri/geometry/scene/pipeline.hpp"
#include "kiri/render/fog_error.hpp"
#include "kiri/render/gl_context.hpp"
#include "kiri/render/image.hpp"
#include "kiri/render/renderer.hpp"
#include "kiri/render/scene_rendering.hpp"

namespace kiri::bench {

//! A scene file as JSON, to vary before parsing it.
struct SceneJson {
    std::filesystem::path file;
    nlohmann::json root;
    explicit SceneJson(std::filesystem::path scene_file);
    geometry::Scene parse(const nlohmann::json& root) const;
};

//! A frame's cost: the median frame time and, per pass, the median device and issue times
//! (FrameStats::passes, in the order of the last frame).
struct FrameCost {
    double frame_ms = 0.0;
    int frames = 0;  //!< how many frames the medians are of
    std::vector<render::PassTime> passes;
    //! The froxel apply's pixels that marched their own rays, of all it applied (last frame; -1: none).
    double marched = -1.0;
    //! Those that took the mean of the marched half-resolution samples around them (-1: none).
    double upsampled = -1.0;
    //! The particles' billboards (last frame): drawn (in view), drawn at the near resolution,
    //! fragments blended.
    int drawn_particles = 0, near_particles = 0;
    std::uint64_t particle_fragments = 0;
};

class FogJudge {
public:
    //! The reference of `base`'s fog (its Medium, and its froxel height fog when the scene has
    //! one) seen from `camera` at width x height. Timed: reference_seconds(). The keys `base`
    //! leaves out are derived from its terrain, here and in prepare(), as kiri render does.
    FogJudge(const geometry::Scene& base, const std::string& camera, int width, int height);
    ~FogJudge();
    double reference_seconds() const { return reference_.seconds; }
    //! The GL context's "OpenGL <version> (<renderer>, <platform>)": which device the times are of.
    std::string gl_description() const { return context_->description(); }
    const geometry::Terrain& terrain() const;
    const geometry::ReferenceImage& reference() const { return reference_; }

    //! Sets the renderer up for `scene` in `mode`; its fog authored by the judge's pipeline (only
    //! the stages whose inputs the scene changed run again).
    void prepare(const geometry::Scene& scene, render::FogMode mode);
    //! Median Renderer draw time (ms) of at least `frames` frames at width x height (and of at
    //! least half a second's, after 0.3 s of untimed frames) while the view moves by a
    //! millimetre a frame (the froxels rerun their passes, as in a moving view).
    double frame_ms(int width, int height, int frames);
    //! The same frames' median time and their passes' median times.
    FrameCost frame_cost(int width, int height, int frames);
    //! The froxel volume's, the terrain grid's and the particles' resolution for the frames that
    //! follow (Renderer::set_froxel_resolution, set_terrain_resolution, set_particle_resolution):
    //! the preview's moving frames.
    void set_reduced_resolution(double scale);
    //! The time (ms) of a still picture at width x height as kiri render draws it: the first
    //! view of the fog, as a still (Renderer::render).
    double still_ms(int width, int height);
    //! The picture still_ms drew.
    const render::Image& still_image() const { return still_image_; }
    //! A still picture at the judge's size against the reference (its per-pixel signed error
    //! into `signed_error` when given: render::compare_frames). \throw kiri::Error when the scene
    //! prepared draws another fog than the reference's (its Medium, its height fog or its sun
    //! differs): a configuration that changes the fog needs a judge of its own.
    render::FogError error(std::vector<float>* signed_error = nullptr);
    //! The last still picture error() drew, tone-mapped (for a look).
    const render::Image& last_image() const { return last_image_; }

private:
    //! The renderer without any fog, nor the fog's shade on the ground.
    void clear_fog();
    //! A frame without fog, resolved and its samples.
    struct Plain {
        render::RadianceImage image;
        render::RadianceSamples samples;
    };
    const Plain& without_fog(bool terrain_shadows);
    //! Without fog and without the sun: the ground's sky light (compare_frames' without_sun).
    const Plain& without_sun();

    //! What the reference drew: the frame judged must draw the same.
    struct ReferenceFog {
        std::shared_ptr<const geometry::Medium> medium;
        geometry::HeightFog height_fog;
        geometry::SunSpec sun;
    };
    //! How the prepared scene's fog differs from the reference's ("" when it does not).
    std::string fog_difference() const;

    geometry::Pipeline pipeline_;
    ReferenceFog reference_fog_;
    render::Camera camera_;
    int width_, height_;
    geometry::ReferenceImage reference_;
    render::SampleReference at_samples_;  //!< through the samples where pixels straddle two surfaces
    std::unique_ptr<render::GlContext> context_;
    std::unique_ptr<render::Renderer> renderer_;
    std::optional<render::SceneRendering> rendering_;
    render::Image last_image_, still_image_;
    std::optional<Plain> plain_[2];  //!< without fog: [terrain shadows off, on]
    std::optional<Plain> sky_lit_;   //!< without fog and sun
};

}  // namespace kiri::bench
